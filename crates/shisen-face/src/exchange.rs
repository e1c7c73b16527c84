//! Export to other tools: the neutral head with morph targets as binary
//! glTF 2.0 (`.glb`). Import of a user's head is in `import.rs`.
//!
//! # Morph targets
//!
//! Each target is `deform(activation) - rest` at weight 1, stored as a
//! sparse accessor (only the vertices it moves):
//!
//! * one per muscle channel, named `<MuscleKind>_L` / `_R` (or no suffix
//!   for procerus and orbicularis oris), at the channel's reference
//!   contraction: the table D value of largest magnitude for that muscle,
//!   sign included (so `OculiUpperPalpebral_L` at weight 1 is surprise's
//!   lid raise, -0.48). (F1) and (F6) are linear in k, so weight w is
//!   contraction `w * reference`; the references are in the mesh's extras
//!   (`shisen.reference`).
//! * `Jaw` at the largest table D jaw angle (14.4 degrees); the rotation
//!   (F7) is linearised by the morph.
//! * ARKit blendshapes from the Action Units at full strength
//!   ([`ARKIT`]), e.g. `mouthSmileLeft` = AU12 on the left side.
//!
//! Target names are in the mesh's `extras.targetNames` (the convention
//! Blender, three.js and Babylon read).
//!
//! The JSON is built by hand with `serde_json`: the document is a few
//! fixed objects, and `json!` shows its structure in a dozen lines where
//! `gltf-json`'s typed builders (every field wrapped in `Checked`/`Index`)
//! take several times that; reading back goes through the `gltf` crate,
//! which validates it.

use glam::Vec3;
use serde_json::json;

use super::emotion::{Activation, AuLevels, Side, channels};
use super::model::Face;
use super::params::FaceParams;
use super::tables::{ActionUnit, MuscleKind};

/// ARKit blendshape name -> Action Unit and side (`Centre` = both sides).
/// AU23 (lip tightener) has no exact ARKit shape; `mouthPress` is the
/// closest. ARKit shapes without an AU in the model (e.g. `mouthPucker`,
/// `eyeLookUp`) are not exported.
pub const ARKIT: [(&str, ActionUnit, Side); 28] = {
    use ActionUnit::*;
    use Side::{Centre as C, Left as L, Right as R};
    [
        ("browInnerUp", Au1, C),
        ("browOuterUpLeft", Au2, L),
        ("browOuterUpRight", Au2, R),
        ("browDownLeft", Au4, L),
        ("browDownRight", Au4, R),
        ("eyeWideLeft", Au5, L),
        ("eyeWideRight", Au5, R),
        ("cheekSquintLeft", Au6, L),
        ("cheekSquintRight", Au6, R),
        ("eyeSquintLeft", Au7, L),
        ("eyeSquintRight", Au7, R),
        ("noseSneerLeft", Au9, L),
        ("noseSneerRight", Au9, R),
        ("mouthUpperUpLeft", Au10, L),
        ("mouthUpperUpRight", Au10, R),
        ("mouthSmileLeft", Au12, L),
        ("mouthSmileRight", Au12, R),
        ("mouthFrownLeft", Au15, L),
        ("mouthFrownRight", Au15, R),
        ("mouthLowerDownLeft", Au16, L),
        ("mouthLowerDownRight", Au16, R),
        ("mouthStretchLeft", Au20, L),
        ("mouthStretchRight", Au20, R),
        ("mouthPressLeft", Au23, L),
        ("mouthPressRight", Au23, R),
        ("jawOpen", Au26, C),
        ("eyeBlinkLeft", Au45, L),
        ("eyeBlinkRight", Au45, R),
    ]
};

/// Reference value of a muscle kind (or the jaw, degrees) for its morph
/// target: the table D value of largest magnitude, sign included; 1 if the
/// database never uses it.
pub fn reference(params: &FaceParams, kind: MuscleKind) -> f64 {
    params
        .expressions
        .values()
        .filter_map(|row| row.get(&kind).copied())
        .max_by(|a, b| a.abs().total_cmp(&b.abs()))
        .unwrap_or(1.0)
}

/// Named morph targets of `face`: (name, reference value, activation).
fn targets(face: &Face) -> Vec<(String, f64, Activation)> {
    let p = &face.params;
    let mut out = Vec::new();
    for (i, id) in channels().into_iter().enumerate() {
        let r = reference(p, id.kind);
        let mut a = Activation::default();
        a.k[i] = r as f32;
        let suffix = match id.side {
            Side::Left => "_L",
            Side::Right => "_R",
            Side::Centre => "",
        };
        out.push((format!("{:?}{suffix}", id.kind), r, a));
    }
    let jaw = reference(p, MuscleKind::Jaw);
    let a = Activation {
        jaw_deg: jaw as f32,
        ..Activation::default()
    };
    out.push(("Jaw".into(), jaw, a));
    for (name, au, side) in ARKIT {
        let mut levels = AuLevels::default();
        let (l, r) = match side {
            Side::Left => (1.0, 0.0),
            Side::Right => (0.0, 1.0),
            Side::Centre => (1.0, 1.0),
        };
        levels.set_sides(au, l, r);
        out.push((name.into(), 1.0, levels.activation(p)));
    }
    out
}

/// Binary buffer under construction: bufferViews and accessors as JSON.
#[derive(Default)]
struct Bin {
    data: Vec<u8>,
    views: Vec<serde_json::Value>,
    accessors: Vec<serde_json::Value>,
}

impl Bin {
    /// Append 4-byte words as a new buffer view; returns its index.
    fn view(&mut self, words: impl Iterator<Item = [u8; 4]>, target: Option<u32>) -> usize {
        let offset = self.data.len();
        for w in words {
            self.data.extend_from_slice(&w);
        }
        let mut v =
            json!({"buffer": 0, "byteOffset": offset, "byteLength": self.data.len() - offset});
        if let Some(t) = target {
            v["target"] = json!(t);
        }
        self.views.push(v);
        self.views.len() - 1
    }

    fn accessor(&mut self, a: serde_json::Value) -> usize {
        self.accessors.push(a);
        self.accessors.len() - 1
    }
}

const FLOAT: u32 = 5126;
const UINT: u32 = 5125;
const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;

fn vec3_words(v: &[Vec3]) -> impl Iterator<Item = [u8; 4]> + '_ {
    v.iter().flat_map(|p| p.to_array()).map(f32::to_le_bytes)
}

fn bounds(v: impl Iterator<Item = Vec3>) -> (Vec3, Vec3) {
    v.fold((Vec3::MAX, Vec3::MIN), |(a, b), p| (a.min(p), b.max(p)))
}

/// The neutral head of `face` as binary glTF 2.0 with morph targets (see
/// the module docs for names and scales).
pub fn export_glb(face: &Face) -> Vec<u8> {
    let mesh = &face.mesh;
    let n = mesh.positions.len();
    let mut bin = Bin::default();
    let (lo, hi) = bounds(mesh.positions.iter().copied());
    let v = bin.view(vec3_words(&mesh.positions), Some(ARRAY_BUFFER));
    let pos = bin.accessor(json!({"bufferView": v, "componentType": FLOAT, "count": n,
        "type": "VEC3", "min": lo.to_array(), "max": hi.to_array()}));
    let v = bin.view(vec3_words(&mesh.normals), Some(ARRAY_BUFFER));
    let nor =
        bin.accessor(json!({"bufferView": v, "componentType": FLOAT, "count": n, "type": "VEC3"}));
    let idx: Vec<u32> = mesh.triangles.iter().flatten().copied().collect();
    let v = bin.view(
        idx.iter().map(|i| i.to_le_bytes()),
        Some(ELEMENT_ARRAY_BUFFER),
    );
    let ind = bin.accessor(json!({"bufferView": v, "componentType": UINT,
        "count": idx.len(), "type": "SCALAR"}));
    let mut out = vec![Vec3::ZERO; n];
    let (mut names, mut refs, mut morphs) = (Vec::new(), Vec::new(), Vec::new());
    for (name, r, a) in targets(face) {
        face.rig.deform(mesh, &a, &mut out);
        let moved: Vec<(u32, Vec3)> = (0..n)
            .map(|i| (i as u32, out[i] - mesh.positions[i]))
            .filter(|(_, d)| d.length_squared() > 1e-14)
            .collect();
        // Unlisted vertices are zero, so the bounds include 0.
        let (lo, hi) = bounds(moved.iter().map(|m| m.1).chain([Vec3::ZERO]));
        let mut acc = json!({"componentType": FLOAT, "count": n, "type": "VEC3",
            "min": lo.to_array(), "max": hi.to_array()});
        if !moved.is_empty() {
            let iv = bin.view(moved.iter().map(|m| m.0.to_le_bytes()), None);
            let d: Vec<Vec3> = moved.iter().map(|m| m.1).collect();
            let vv = bin.view(vec3_words(&d), None);
            acc["sparse"] = json!({"count": moved.len(),
                "indices": {"bufferView": iv, "componentType": UINT},
                "values": {"bufferView": vv}});
        }
        morphs.push(json!({"POSITION": bin.accessor(acc)}));
        names.push(name);
        refs.push(r);
    }
    let doc = json!({
        "asset": {"version": "2.0", "generator": "shisen face exchange"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": "head"}],
        "meshes": [{
            "name": "head",
            "primitives": [{"attributes": {"POSITION": pos, "NORMAL": nor},
                "indices": ind, "mode": 4, "targets": morphs}],
            "weights": vec![0.0; names.len()],
            "extras": {"targetNames": names, "shisen": {"reference": refs}},
        }],
        "buffers": [{"byteLength": bin.data.len()}],
        "bufferViews": bin.views,
        "accessors": bin.accessors,
    });
    glb(&serde_json::to_vec(&doc).expect("JSON"), bin.data)
}

/// GLB container: header, JSON chunk (space padded), BIN chunk (zero padded).
fn glb(json: &[u8], mut data: Vec<u8>) -> Vec<u8> {
    let mut json = json.to_vec();
    json.resize(json.len().next_multiple_of(4), b' ');
    data.resize(data.len().next_multiple_of(4), 0);
    let total = 12 + 8 + json.len() + 8 + data.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    out.extend_from_slice(&(data.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&data);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::emotion::MuscleId;
    use crate::mesh::MeshParams;

    fn face(rows: usize) -> Face {
        Face::new(MeshParams { rows }, FaceParams::default_params())
    }

    fn channel(kind: MuscleKind, side: Side) -> usize {
        MuscleId { kind, side }.index().unwrap()
    }

    #[test]
    fn export_round_trips_through_the_gltf_crate() {
        let f = face(32);
        let glb = export_glb(&f);
        let g = gltf::Gltf::from_slice(&glb).expect("valid glTF");
        let blob = g.blob.as_deref().unwrap();
        let mesh = g.meshes().next().unwrap();
        let prim = mesh.primitives().next().unwrap();
        let r = prim.reader(|_| Some(blob));
        let n = f.mesh.positions.len();
        assert_eq!(r.read_positions().unwrap().count(), n);
        assert_eq!(
            r.read_indices().unwrap().into_u32().count(),
            3 * f.mesh.triangles.len()
        );
        let extras: serde_json::Value =
            serde_json::from_str(mesh.extras().as_ref().unwrap().get()).unwrap();
        let names: Vec<String> = serde_json::from_value(extras["targetNames"].clone()).unwrap();
        assert_eq!(prim.morph_targets().count(), 28 + 1 + ARKIT.len());
        assert_eq!(names.len(), prim.morph_targets().count());
        for want in [
            "ZygomaticMajor_L",
            "Procerus",
            "Jaw",
            "jawOpen",
            "eyeBlinkLeft",
        ] {
            assert!(names.iter().any(|n| n == want), "{want}");
        }
        // A target's sparse values are the rig's displacement.
        let t = names.iter().position(|n| n == "ZygomaticMajor_L").unwrap();
        let (d, _, _) = r.read_morph_targets().nth(t).unwrap();
        let d: Vec<Vec3> = d.unwrap().map(Vec3::from_array).collect();
        assert_eq!(d.len(), n);
        let mut a = Activation::default();
        a.k[channel(MuscleKind::ZygomaticMajor, Side::Left)] = 0.19;
        let mut out = vec![Vec3::ZERO; n];
        f.rig.deform(&f.mesh, &a, &mut out);
        let err = (0..n)
            .map(|i| (out[i] - f.mesh.positions[i] - d[i]).length())
            .fold(0.0f32, f32::max);
        assert!(err < 1e-6, "target differs from the rig by {err}");
        assert!(d.iter().any(|v| v.length() > 0.002));
        println!("glb of {n} vertices: {} kB", glb.len() / 1024);
    }
}
