//! Import a user's head (OBJ via `tobj`, or `.glb` via `gltf`) plus a
//! landmark file that places the muscles, so the imported mesh deforms with
//! the same rig ([`Face::from_mesh`]).
//!
//! The mesh must be in the head frame of `mesh.rs` (metres after `scale`,
//! +Y up, +Z forward, +X the agent's left, the face's midline at x = 0),
//! as the rig mirrors left-side landmarks to place the right-side muscles.
//! The landmark file (RON) names every field of [`Landmarks`] for the
//! agent's left side, each as `Vertex(i)` (0-based index in the file's own
//! vertex list: OBJ `v` lines in order, or the glTF POSITION accessor) or
//! `Point(x, y, z)`:
//!
//! ```text
//! (
//!     scale: 0.01, // optional: centimetres -> metres
//!     jaw_half_width: 0.06,
//!     landmarks: {
//!         "nasion": Vertex(812),
//!         "eye_centre": Point(0.031, 0.0, 0.0),
//!         ...
//!     },
//! )
//! ```

use std::collections::BTreeMap;
use std::path::Path;

use glam::Vec3;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::mesh::{HeadMesh, Landmarks, Rims, compute_normals, lid_zone};
use super::model::Face;
use super::params::FaceError;
use super::params::FaceParams;

/// A landmark given by vertex index or position (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub enum LandmarkRef {
    /// 0-based index into the imported file's vertex list, at most
    /// 2^32 - 1 (the mesh's triangles index vertices with 32 bits; an
    /// index past the file's vertices is refused when the mesh is read).
    Vertex(#[schemars(range(min = 0, max = 4_294_967_295_u64))] usize),
    /// Position `(x, y, z)` in the file's units (scaled by `scale`), each
    /// within +-1e6 units: a head some 0.2 m across written in units as
    /// small as `scale`'s smallest, a micrometre.
    Point(
        #[schemars(range(min = -1.0e6, max = 1.0e6))] f32,
        #[schemars(range(min = -1.0e6, max = 1.0e6))] f32,
        #[schemars(range(min = -1.0e6, max = 1.0e6))] f32,
    ),
}

/// Landmark file contents (RON).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LandmarkFile {
    /// Factor from the file's units to metres (default 1), 1e-6-10: from
    /// a file in micrometres to one in decametres; 0.001 for millimetres,
    /// 0.01 for centimetres, 0.0254 for inches.
    #[serde(default = "one")]
    #[schemars(range(min = 1.0e-6, max = 10.0))]
    pub scale: f32,
    /// Midline to the jaw's outer edge (F7's L), metres (not scaled by
    /// `scale`), 0.01-0.25: an adult's is about 5 cm (bigonial breadth
    /// about 10 cm, Farkas 1994, Anthropometry of the Head and Face); the
    /// bounds are a fifth and five times that.
    #[schemars(range(min = 0.01, max = 0.25))]
    pub jaw_half_width: f32,
    /// Named landmarks (the fields of [`Landmarks`]; every one of
    /// [`LANDMARK_NAMES`] must be given, and no other).
    pub landmarks: BTreeMap<String, LandmarkRef>,
}

fn one() -> f32 {
    1.0
}

impl LandmarkFile {
    /// Parse a landmark file; errors name the file, line and field.
    pub fn parse(text: &str, file: &Path) -> Result<Self, FaceError> {
        Ok(shisen_gaze::util::ron::parse_ron(text, file)?)
    }

    /// A landmark file giving `l` as points (metres): a template for a
    /// user's head, or the generated head's own landmarks.
    pub fn from_landmarks(l: &Landmarks) -> LandmarkFile {
        let all = [
            l.nasion,
            l.glabella,
            l.nasal_bone,
            l.nose_tip,
            l.nostril_wing,
            l.brow_inner,
            l.brow_mid,
            l.brow_outer,
            l.forehead_inner,
            l.forehead_mid,
            l.forehead_outer,
            l.orbit_inner_upper,
            l.orbit_inner_lower,
            l.orbit_lower,
            l.cheekbone,
            l.face_side,
            l.eye_inner_corner,
            l.eye_outer_corner,
            l.upper_lid_mid,
            l.lower_lid_mid,
            l.eye_centre,
            l.mouth_corner,
            l.mouth_centre,
            l.upper_lip,
            l.lower_lip,
            l.jaw_lower_edge,
            l.jaw_outer,
            l.chin,
            l.jaw_pivot,
            l.ear_lobe,
        ];
        let landmarks = LANDMARK_NAMES
            .iter()
            .zip(all)
            .map(|(n, p)| (n.to_string(), LandmarkRef::Point(p.x, p.y, p.z)))
            .collect();
        LandmarkFile {
            scale: 1.0,
            jaw_half_width: l.jaw_half_width,
            landmarks,
        }
    }

    /// The file as RON text that [`LandmarkFile::parse`] reads back.
    pub fn to_ron(&self) -> String {
        let cfg = ron::ser::PrettyConfig::new().indentor("    ".to_string());
        ron::ser::to_string_pretty(self, cfg).expect("plain data serialises")
    }

    /// Resolve every landmark against `positions` (already scaled).
    pub fn resolve(&self, positions: &[Vec3]) -> Result<Landmarks, FaceError> {
        let get = |name: &str| -> Result<Vec3, FaceError> {
            match self.landmarks.get(name) {
                None => Err(FaceError::Import(format!("landmark `{name}` missing"))),
                Some(LandmarkRef::Point(x, y, z)) => Ok(Vec3::new(*x, *y, *z) * self.scale),
                Some(LandmarkRef::Vertex(i)) => positions.get(*i).copied().ok_or_else(|| {
                    FaceError::Import(format!(
                        "landmark `{name}`: vertex {i} out of range ({} vertices)",
                        positions.len()
                    ))
                }),
            }
        };
        let l = Landmarks {
            nasion: get("nasion")?,
            glabella: get("glabella")?,
            nasal_bone: get("nasal_bone")?,
            nose_tip: get("nose_tip")?,
            nostril_wing: get("nostril_wing")?,
            brow_inner: get("brow_inner")?,
            brow_mid: get("brow_mid")?,
            brow_outer: get("brow_outer")?,
            forehead_inner: get("forehead_inner")?,
            forehead_mid: get("forehead_mid")?,
            forehead_outer: get("forehead_outer")?,
            orbit_inner_upper: get("orbit_inner_upper")?,
            orbit_inner_lower: get("orbit_inner_lower")?,
            orbit_lower: get("orbit_lower")?,
            cheekbone: get("cheekbone")?,
            face_side: get("face_side")?,
            eye_inner_corner: get("eye_inner_corner")?,
            eye_outer_corner: get("eye_outer_corner")?,
            upper_lid_mid: get("upper_lid_mid")?,
            lower_lid_mid: get("lower_lid_mid")?,
            eye_centre: get("eye_centre")?,
            mouth_corner: get("mouth_corner")?,
            mouth_centre: get("mouth_centre")?,
            upper_lip: get("upper_lip")?,
            lower_lip: get("lower_lip")?,
            jaw_lower_edge: get("jaw_lower_edge")?,
            jaw_outer: get("jaw_outer")?,
            chin: get("chin")?,
            jaw_pivot: get("jaw_pivot")?,
            ear_lobe: get("ear_lobe")?,
            jaw_half_width: self.jaw_half_width,
        };
        if let Some(extra) = self
            .landmarks
            .keys()
            .find(|k| !LANDMARK_NAMES.contains(&k.as_str()))
        {
            return Err(FaceError::Import(format!("unknown landmark `{extra}`")));
        }
        Ok(l)
    }
}

/// The landmark names a landmark file gives (the fields of [`Landmarks`]).
pub const LANDMARK_NAMES: [&str; 30] = [
    "nasion",
    "glabella",
    "nasal_bone",
    "nose_tip",
    "nostril_wing",
    "brow_inner",
    "brow_mid",
    "brow_outer",
    "forehead_inner",
    "forehead_mid",
    "forehead_outer",
    "orbit_inner_upper",
    "orbit_inner_lower",
    "orbit_lower",
    "cheekbone",
    "face_side",
    "eye_inner_corner",
    "eye_outer_corner",
    "upper_lid_mid",
    "lower_lid_mid",
    "eye_centre",
    "mouth_corner",
    "mouth_centre",
    "upper_lip",
    "lower_lip",
    "jaw_lower_edge",
    "jaw_outer",
    "chin",
    "jaw_pivot",
    "ear_lobe",
];

/// A head mesh from raw positions (file units), triangles and landmarks:
/// scaled, normals computed, lid zones around the eye centres, no rims.
pub fn head_from_parts(
    positions: Vec<Vec3>,
    triangles: Vec<[u32; 3]>,
    lm: &LandmarkFile,
) -> Result<HeadMesh, FaceError> {
    let positions: Vec<Vec3> = positions.into_iter().map(|p| p * lm.scale).collect();
    if triangles.is_empty() {
        return Err(FaceError::Import(
            "an empty mesh: no triangles to make a head of".into(),
        ));
    }
    if let Some((i, p)) = positions.iter().enumerate().find(|(_, p)| !p.is_finite()) {
        return Err(FaceError::Import(format!(
            "vertex {i} is not a finite point ({p})"
        )));
    }
    if let Some(t) = triangles
        .iter()
        .find(|t| t.iter().any(|&i| i as usize >= positions.len()))
    {
        return Err(FaceError::Import(format!(
            "triangle {t:?} indexes past the vertices"
        )));
    }
    let landmarks = lm.resolve(&positions)?;
    check_landmarks(&landmarks)?;
    Ok(HeadMesh {
        normals: compute_normals(&positions, &triangles),
        lid_zone: lid_zone(&positions, landmarks.eye_centre),
        positions,
        coarse: triangles.clone(),
        medium: triangles.clone(),
        medium_error: 0.0,
        triangles,
        landmarks,
        rims: Rims::default(),
    })
}

/// Landmarks that cannot be a face's: gathered at a point, or the eye on
/// the mid-plane (the two eyes would be one). A head's landmarks span
/// some 15-25 cm from the forehead to the chin and the ear; its eye
/// centres are about 6 cm apart.
fn check_landmarks(l: &Landmarks) -> Result<(), FaceError> {
    let points = [
        l.forehead_mid,
        l.nasion,
        l.nose_tip,
        l.eye_centre,
        l.mouth_centre,
        l.chin,
        l.jaw_pivot,
        l.ear_lobe,
    ];
    let lo = points.iter().copied().fold(Vec3::INFINITY, Vec3::min);
    let hi = points.iter().copied().fold(Vec3::NEG_INFINITY, Vec3::max);
    let span = (hi - lo).length();
    if span < 0.08 {
        return Err(FaceError::Import(format!(
            "the landmarks span {span:.3} m (after `scale`): a head's span 0.15-0.25 m from forehead to chin and ear"
        )));
    }
    if l.eye_centre.x.abs() < 0.01 {
        return Err(FaceError::Import(format!(
            "the eye centre is {:.3} m from the mid-plane: the eyes would meet (a head's are about 0.03 m each side)",
            l.eye_centre.x.abs()
        )));
    }
    Ok(())
}

fn import_err(file: &Path, e: impl std::fmt::Display) -> FaceError {
    FaceError::Import(format!("{}: {e}", file.display()))
}

/// Head mesh from OBJ text (all objects merged, polygons triangulated,
/// vertex indices as in the file's `v` lines) and a landmark file.
/// Vertices at bit-identical positions are welded onto the first of them.
pub fn mesh_from_obj(obj: &str, lm: &LandmarkFile, file: &Path) -> Result<HeadMesh, FaceError> {
    // The struct's fields depend on tobj's features: keep the update syntax.
    #[allow(clippy::needless_update)]
    let opts = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
        ..Default::default()
    };
    let (models, _) = tobj::load_obj_buf(&mut obj.as_bytes(), &opts, |_| {
        Err(tobj::LoadError::GenericFailure)
    })
    .map_err(|e| import_err(file, e))?;
    // tobj renumbers vertices per object in order of use; map them back to
    // the file's `v` order (landmark indices refer to that) by the `v` lines.
    let mut positions = Vec::new();
    for (n, line) in obj.lines().enumerate() {
        let mut f = line.split_whitespace();
        if f.next() != Some("v") {
            continue;
        }
        let c: Vec<f32> = f.take(3).filter_map(|x| x.parse().ok()).collect();
        if c.len() < 3 {
            return Err(import_err(file, format!("line {}: bad vertex", n + 1)));
        }
        positions.push(Vec3::new(c[0], c[1], c[2]));
    }
    let mut lookup: BTreeMap<[u32; 3], u32> = BTreeMap::new();
    for (i, p) in positions.iter().enumerate() {
        lookup
            .entry(p.to_array().map(f32::to_bits))
            .or_insert(i as u32);
    }
    let mut triangles = Vec::new();
    for m in &models {
        let pos = &m.mesh.positions;
        let global = |i: u32| {
            let k = 3 * i as usize;
            let key = [pos[k], pos[k + 1], pos[k + 2]].map(f32::to_bits);
            lookup
                .get(&key)
                .copied()
                .ok_or_else(|| import_err(file, "a face vertex matches no `v` line"))
        };
        for t in m.mesh.indices.chunks_exact(3) {
            triangles.push([global(t[0])?, global(t[1])?, global(t[2])?]);
        }
    }
    head_from_parts(positions, triangles, lm)
}

/// Head mesh from binary glTF: every triangle primitive of the first mesh
/// (untransformed), vertex indices counted across them in order.
pub fn mesh_from_glb(glb: &[u8], lm: &LandmarkFile, file: &Path) -> Result<HeadMesh, FaceError> {
    let g = gltf::Gltf::from_slice(glb).map_err(|e| import_err(file, e))?;
    let blob = g.blob.as_deref();
    let mesh = g
        .meshes()
        .next()
        .ok_or_else(|| import_err(file, "no mesh"))?;
    let (mut positions, mut triangles) = (Vec::new(), Vec::new());
    for prim in mesh
        .primitives()
        .filter(|p| p.mode() == gltf::mesh::Mode::Triangles)
    {
        let r = prim.reader(|b| match b.source() {
            gltf::buffer::Source::Bin => blob,
            gltf::buffer::Source::Uri(_) => None,
        });
        let base = positions.len() as u32;
        let p = r
            .read_positions()
            .ok_or_else(|| import_err(file, "no POSITION"))?;
        positions.extend(p.map(Vec3::from_array));
        let count = positions.len() as u32 - base;
        let idx: Vec<u32> = match r.read_indices() {
            Some(i) => i.into_u32().collect(),
            None => (0..count).collect(),
        };
        triangles.extend(
            idx.chunks_exact(3)
                .map(|t| [t[0] + base, t[1] + base, t[2] + base]),
        );
    }
    head_from_parts(positions, triangles, lm)
}

/// Import a head (`.obj`, or `.glb` with embedded buffer) and its landmark
/// file, and build the face with `params`.
pub fn import(mesh: &Path, landmarks: &Path, params: FaceParams) -> Result<Face, FaceError> {
    let lm_text = std::fs::read_to_string(landmarks).map_err(|e| import_err(landmarks, e))?;
    let lm = LandmarkFile::parse(&lm_text, landmarks)?;
    let bytes = std::fs::read(mesh).map_err(|e| import_err(mesh, e))?;
    let head = if bytes.starts_with(b"glTF") {
        mesh_from_glb(&bytes, &lm, mesh)?
    } else {
        let text = String::from_utf8(bytes).map_err(|e| import_err(mesh, e))?;
        mesh_from_obj(&text, &lm, mesh)?
    };
    Ok(Face::from_mesh(head, params))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::emotion::{Activation, MuscleId, Side};
    use crate::exchange::export_glb;
    use crate::mesh::MeshParams;
    use crate::tables::MuscleKind;

    fn face(rows: usize) -> Face {
        Face::new(MeshParams { rows }, FaceParams::default_params())
    }

    fn channel(kind: MuscleKind, side: Side) -> usize {
        MuscleId { kind, side }.index().unwrap()
    }

    fn obj_text(m: &HeadMesh) -> String {
        let mut s = String::from("# generated head\no head\n");
        for p in &m.positions {
            s += &format!("v {:?} {:?} {:?}\n", p.x, p.y, p.z);
        }
        for t in &m.triangles {
            s += &format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
        }
        s
    }

    #[test]
    fn imported_obj_with_landmarks_gets_the_same_rig() {
        let f = face(32);
        let mut lm = LandmarkFile::from_landmarks(&f.mesh.landmarks);
        let corner = *f.mesh.rims.upper_lip.last().unwrap();
        lm.landmarks
            .insert("mouth_corner".into(), LandmarkRef::Vertex(corner as usize));
        let lm = LandmarkFile::parse(&lm.to_ron(), Path::new("lm.ron")).unwrap();
        let head = mesh_from_obj(&obj_text(&f.mesh), &lm, Path::new("head.obj")).unwrap();
        assert_eq!(head.positions, f.mesh.positions);
        assert_eq!(head.triangles, f.mesh.triangles);
        assert_eq!(head.lid_zone, f.mesh.lid_zone);
        let g = Face::from_mesh(head, FaceParams::default_params());
        let zyg = channel(MuscleKind::ZygomaticMajor, Side::Left);
        assert_eq!(g.rig.fields[zyg], f.rig.fields[zyg]);
        // The zygomatic field moves the mouth corner up and outward.
        let mut a = Activation::default();
        a.k[zyg] = 0.19;
        let mut out = vec![Vec3::ZERO; g.mesh.positions.len()];
        g.rig.deform(&g.mesh, &a, &mut out);
        let d = out[corner as usize] - g.mesh.positions[corner as usize];
        println!("mouth corner moves {:.2} mm", d.length() * 1000.0);
        assert!(d.y > 0.001 && d.x > 0.0, "{d}");
        // The same head read from the exported glb.
        let h = mesh_from_glb(&export_glb(&f), &lm, Path::new("head.glb")).unwrap();
        assert_eq!(h.positions, f.mesh.positions);
        assert_eq!(h.triangles, f.mesh.triangles);
    }

    /// A mesh with no triangles, a vertex at NaN, or landmarks gathered at
    /// one point make no head: refused, not a face of floating eyes.
    #[test]
    fn meshes_and_landmarks_that_make_no_head_are_refused() {
        let f = face(24);
        let lm = LandmarkFile::from_landmarks(&f.mesh.landmarks);
        let m = &f.mesh;
        let e = head_from_parts(m.positions.clone(), Vec::new(), &lm).unwrap_err();
        assert!(e.to_string().contains("empty mesh"), "{e}");
        let mut nan = m.positions.clone();
        nan[3].y = f32::NAN;
        let e = head_from_parts(nan, m.triangles.clone(), &lm).unwrap_err();
        assert!(e.to_string().contains("vertex 3"), "{e}");
        let mut one = lm.clone();
        for v in one.landmarks.values_mut() {
            *v = LandmarkRef::Vertex(0);
        }
        let e = head_from_parts(m.positions.clone(), m.triangles.clone(), &one).unwrap_err();
        assert!(e.to_string().contains("span"), "{e}");
        assert!(head_from_parts(m.positions.clone(), m.triangles.clone(), &lm).is_ok());
    }

    #[test]
    fn landmark_errors() {
        let f = face(24);
        let mut lm = LandmarkFile::from_landmarks(&f.mesh.landmarks);
        lm.landmarks.remove("chin");
        let e = lm.resolve(&f.mesh.positions).unwrap_err().to_string();
        assert!(e.contains("`chin` missing"), "{e}");
        lm.landmarks
            .insert("chin".into(), LandmarkRef::Vertex(1 << 30));
        let e = lm.resolve(&f.mesh.positions).unwrap_err().to_string();
        assert!(e.contains("out of range"), "{e}");
        let e = LandmarkFile::parse(
            "(jaw_half_width: 0.06, landmarks: {}, x: 1)",
            Path::new("l.ron"),
        )
        .unwrap_err()
        .to_string();
        assert!(e.starts_with("l.ron:1:"), "{e}");
        // Every number has a range: a scale of 0, a jaw given in
        // millimetres, a vertex index past 32 bits, a point at NaN.
        for (text, named) in [
            (
                "(scale: 0.0, jaw_half_width: 0.06, landmarks: {})",
                "l.ron:1:2: scale: must be >= ",
            ),
            (
                "(jaw_half_width: 60.0, landmarks: {})",
                "l.ron:1:2: jaw_half_width: must be <= 0.25",
            ),
            (
                "(jaw_half_width: 0.06,\n landmarks: {\"chin\": Vertex(5000000000)})",
                "l.ron:2:14: landmarks.chin.Vertex: must be <= 4294967295",
            ),
            (
                "(jaw_half_width: 0.06, landmarks: {\"chin\": Point(0.0, NaN, 0.0)})",
                "landmarks.chin.Point[1]: must be a finite number",
            ),
        ] {
            let e = LandmarkFile::parse(text, Path::new("l.ron"))
                .unwrap_err()
                .to_string();
            assert!(e.contains(named), "{text}: {e}");
        }
    }
}
