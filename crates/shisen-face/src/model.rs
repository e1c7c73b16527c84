//! The face model ([`Face`], static) and its evolving state ([`FaceState`]).

use super::blink::BlinkProcess;
use super::emotion::{Activation, AuLevels, MuscleId, Side, emotion_activation};
use super::mesh::{HeadMesh, MeshParams};
use super::params::FaceParams;
use super::reflex::ReflexState;
use super::rig::Rig;
use super::tables::{Emotion, MuscleKind};
use super::timing::{OffsetGroup, Pattern, Speed, Transition, transition_duration};
use glam::Vec3;
use rand::Rng;

/// Static face description: mesh, placed muscles and fields, parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct Face {
    /// Rest mesh with landmarks.
    pub mesh: HeadMesh,
    /// Measured parameters.
    pub params: FaceParams,
    /// Muscles and precomputed fields.
    pub rig: Rig,
    /// Colours of the skin (tone, flush, lash line) and borders of the
    /// lips, brows and hair on the rest vertices
    /// ([`super::appearance::paint`]).
    pub paint: super::appearance::Paint,
    /// Rest frames for measuring the skin's compression (wrinkles).
    pub wrinkle_basis: super::wrinkle::WrinkleBasis,
}

impl Face {
    /// Generate the head and build the rig.
    pub fn new(mesh: MeshParams, params: FaceParams) -> Face {
        let mesh = HeadMesh::generate(mesh);
        Face::from_mesh(mesh, params)
    }

    /// Build the rig on a given mesh (generated or imported, see `exchange.rs`).
    pub fn from_mesh(mesh: HeadMesh, params: FaceParams) -> Face {
        let rig = Rig::build(&mesh, &params);
        let paint = super::appearance::paint(&mesh, &super::appearance::FaceStyle::DEFAULT);
        let wrinkle_basis = super::wrinkle::WrinkleBasis::new(&mesh, &params.skin);
        Face {
            mesh,
            params,
            rig,
            paint,
            wrinkle_basis,
        }
    }
}

/// Everything that evolves: current contractions, the expression
/// transition, direct AU levels, the blink process and the eye pitch.
#[derive(Clone, Debug, PartialEq)]
pub struct FaceState {
    /// Composed contractions consumed by [`deform`] (updated by [`FaceState::step`]).
    pub activation: Activation,
    /// Current target emotion.
    pub emotion: Emotion,
    /// Its intensity in [0, 1].
    pub intensity: f32,
    /// Expression transition (timing).
    pub transition: Transition,
    /// Direct AU control, added to the expression.
    pub au: AuLevels,
    /// Blink process.
    pub blink: BlinkProcess,
    /// Vertical rotation of each eye (0 left, 1 right), radians, positive up;
    /// the upper lids follow it.
    pub eye_pitch: [f32; 2],
    /// Offset viewer group (table 5.10).
    pub offset_group: OffsetGroup,
    /// The VH is busy sparring (guarding or attacking): blinks come less
    /// often ([`super::params::BlinkParams::engaged_interval_scale`]).
    pub engaged: bool,
    /// Reflex blinks and the wince (F9).
    pub reflex: ReflexState,
    /// Effort shown on the face (a tiring fighter's strained brow and
    /// open-mouthed breathing), set each tick by the body's state and
    /// added like `au`.
    pub effort: AuLevels,
}

impl Default for FaceState {
    fn default() -> Self {
        Self {
            activation: Activation::default(),
            emotion: Emotion::Neutral,
            intensity: 0.0,
            transition: Transition::at_rest(Activation::default()),
            au: AuLevels::default(),
            blink: BlinkProcess::default(),
            eye_pitch: [0.0; 2],
            offset_group: OffsetGroup::One,
            engaged: false,
            reflex: ReflexState::default(),
            effort: AuLevels::default(),
        }
    }
}

impl FaceState {
    /// Start a change to `emotion` at `intensity` from the current values,
    /// lasting the table 5.9 / 5.10 duration at `speed` (face.md 7).
    pub fn set_emotion(
        &mut self,
        face: &Face,
        emotion: Emotion,
        intensity: f32,
        speed: Speed,
        pattern: Pattern,
    ) {
        let t = transition_duration(
            &face.params,
            self.emotion.regions(),
            emotion.regions(),
            speed,
            self.offset_group,
        );
        self.transition.retarget(
            emotion_activation(&face.params, emotion, intensity),
            t,
            pattern,
        );
        self.emotion = emotion;
        self.intensity = intensity;
    }

    /// Report a gaze shift (may trigger a blink; see `blink.rs`).
    pub fn gaze_shift(&mut self, face: &Face, amplitude_deg: f64, rng: &mut impl Rng) -> bool {
        self.blink
            .gaze_shift(&face.params.blink, amplitude_deg, rng)
    }

    /// A blow of `impulse` N s struck the head: a reflex blink and a wince
    /// follow (F9).
    pub fn struck(&mut self, face: &Face, impulse: f64) {
        self.reflex.struck(&face.params.reflex, impulse);
    }

    /// A glove is seen closing on the eyes: a reflex blink follows.
    pub fn threat(&mut self, face: &Face) {
        self.reflex.threat(&face.params.reflex);
    }

    /// Advance by `dt` seconds and recompose [`FaceState::activation`]:
    /// transition value + direct AUs; both palpebral parts then get the
    /// lid-follow contraction for the eye pitch, and the upper one the blink:
    /// `k <- k + b (k45 - k)` with b the AU45 level (so a blink closes the
    /// lid fully from any expression). Spontaneous blinks occur only in
    /// neutral when `blink.neutral_only` is set (the thesis's rule); their
    /// rate drops while sparring and rises with arousal.
    pub fn step(&mut self, face: &Face, dt: f64, rng: &mut impl Rng) {
        let bp = &face.params.blink;
        self.transition.advance(dt);
        let allowed = !bp.neutral_only || self.emotion == Emotion::Neutral;
        let situation = if self.engaged {
            bp.engaged_interval_scale
        } else {
            1.0
        };
        let arousal = self.emotion.arousal() * f64::from(self.intensity);
        let scale = situation / (1.0 + bp.arousal_gain * arousal);
        self.blink.step(bp, dt, allowed, scale, rng);
        if self.reflex.step(&face.params.reflex, dt) && self.blink.blink_time.is_none() {
            self.blink.reflex_blink();
        }
        let mut a = self
            .transition
            .value()
            .add(&self.au.activation(&face.params));
        if self.effort != AuLevels::default() {
            a = a.add(&self.effort.activation(&face.params));
        }
        if let Some(w) = self.reflex.activation(&face.params) {
            a = a.add(&w);
        }
        let b = self.blink.closure(bp) as f32;
        for (e, side) in [Side::Left, Side::Right].into_iter().enumerate() {
            let pitch = self.eye_pitch[e];
            let ch = |kind| MuscleId { kind, side }.index().expect("channel");
            let lower = ch(MuscleKind::OculiLowerPalpebral);
            a.k[lower] += face
                .rig
                .lid_follow_k(e, 1, pitch, bp.lower_lid_follow_gain as f32);
            // AU 6's cheek pushes the lower lid up.
            let orbital = a.k[ch(MuscleKind::OculiOrbital)].max(0.0);
            a.k[lower] += face.rig.lid_k(e, 1, bp.cheek_lid_rise_m as f32 * orbital); // (L2)
            let i = ch(MuscleKind::OculiUpperPalpebral);
            // A relaxation (AU 5) stands for levator's raise.
            let expressed = face.rig.levator_k(
                e,
                a.k[i],
                bp.levator_gain as f32,
                bp.levator_max_raise_m.map(|r| r as f32),
            );
            let k = expressed
                + face
                    .rig
                    .lid_follow_k(e, 0, pitch, bp.lid_follow_gain as f32);
            a.k[i] = k + b * (bp.contraction as f32 - k);
        }
        self.activation = a;
    }
}

/// Write the deformed vertex positions for `state` into `out` (length =
/// vertex count): rest + sum k field + jaw, lids kept over the eyeballs.
pub fn deform(face: &Face, state: &FaceState, out: &mut [Vec3]) {
    face.rig.deform(&face.mesh, &state.activation, out);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::dims;
    use crate::tables::ActionUnit;
    use rand::SeedableRng;
    use rand::rngs::StdRng;

    fn face(rows: usize) -> Face {
        Face::new(MeshParams { rows }, FaceParams::default_params())
    }

    fn deformed(f: &Face, a: Activation) -> Vec<Vec3> {
        let mut out = vec![Vec3::ZERO; f.mesh.positions.len()];
        f.rig.deform(&f.mesh, &a, &mut out);
        out
    }

    #[test]
    fn bilateral_aus_keep_the_face_symmetric() {
        let f = face(32);
        let rest = &f.mesh.positions;
        // Mirror partner of every vertex (brute force; the mesh is symmetric).
        let partner: Vec<usize> = rest
            .iter()
            .map(|p| {
                let m = Vec3::new(-p.x, p.y, p.z);
                (0..rest.len())
                    .min_by(|&a, &b| {
                        rest[a]
                            .distance_squared(m)
                            .total_cmp(&rest[b].distance_squared(m))
                    })
                    .unwrap()
            })
            .collect();
        let rest_asym = rest
            .iter()
            .zip(&partner)
            .map(|(p, &j)| p.distance(Vec3::new(-rest[j].x, rest[j].y, rest[j].z)))
            .fold(0.0f32, f32::max);
        assert!(rest_asym < 1e-5, "rest asymmetry {rest_asym}");
        let mut au = AuLevels::default();
        for a in ActionUnit::ALL {
            if a != ActionUnit::Au5 && a != ActionUnit::Au45 {
                au.set(a, 1.0);
            }
        }
        for act in [
            au.activation(&f.params),
            emotion_activation(&f.params, Emotion::Surprise, 1.0),
            emotion_activation(&f.params, Emotion::Anger, 1.0),
        ] {
            let d = deformed(&f, act);
            let asym = d
                .iter()
                .zip(&partner)
                .map(|(p, &j)| p.distance(Vec3::new(-d[j].x, d[j].y, d[j].z)))
                .fold(0.0f32, f32::max);
            println!("max asymmetry {:.4} mm", asym * 1000.0);
            assert!(asym < 1e-5, "asymmetry {asym} m");
            // And the face did move.
            assert!(d.iter().zip(rest).any(|(a, b)| a.distance(*b) > 0.002));
        }
    }

    #[test]
    fn blink_closes_the_whole_fissure_and_surprise_raises_the_lid() {
        for rows in [40, 100, 224] {
            let f = face(rows);
            let mut a = Activation::default();
            a.set_kind(MuscleKind::OculiUpperPalpebral, 2.9);
            let d = deformed(&f, a);
            let mut worst = 0.0f32;
            for e in 0..2 {
                let centre = f.rig.eye_centres[e];
                let (up, low) = (&f.mesh.rims.upper_lid[e], &f.mesh.rims.lower_lid[e]);
                // Same columns: the i-th upper and lower rim vertices share x.
                for (&u, &l) in up.iter().zip(low) {
                    let (pu, pl) = (d[u as usize], d[l as usize]);
                    worst = worst.max(pu.distance(pl));
                    assert!(
                        pu.distance(centre) >= dims::EYEBALL_R && pu.z > centre.z,
                        "rows {rows}: rim vertex {pu} not over the eyeball"
                    );
                }
                // Lower lid untouched by the upper palpebral part.
                for &i in low {
                    assert!(d[i as usize].distance(f.mesh.positions[i as usize]) < 1e-6);
                }
            }
            println!(
                "rows {rows}: AU45 2.9, max upper-to-lower rim gap {:.3} mm",
                worst * 1000.0
            );
            assert!(worst < 0.001, "rows {rows}: fissure left open by {worst} m");
            // Surprise: relaxed upper palpebral raises the lid.
            let s = emotion_activation(&f.params, Emotion::Surprise, 1.0);
            let d = deformed(&f, s);
            let mid = f.mesh.rims.upper_lid[0][f.mesh.rims.upper_lid[0].len() / 2] as usize;
            let rise = d[mid].y - f.mesh.positions[mid].y;
            println!("rows {rows}: surprise lid rise {:.2} mm", rise * 1000.0);
            assert!(rise > 0.0008);
        }
    }

    #[test]
    fn jaw_drop_moves_chin_and_not_the_nose() {
        let f = face(60);
        let a = Activation {
            jaw_deg: 14.4,
            ..Activation::default()
        };
        let d = deformed(&f, a);
        let rest = &f.mesh.positions;
        let chin = (0..rest.len())
            .min_by(|&i, &j| {
                rest[i]
                    .distance(f.mesh.landmarks.chin)
                    .total_cmp(&rest[j].distance(f.mesh.landmarks.chin))
            })
            .unwrap();
        let r0 = rest[chin] - f.rig.jaw.pivot;
        let r1 = d[chin] - f.rig.jaw.pivot;
        let ang = Vec3::new(0.0, r0.y, r0.z)
            .angle_between(Vec3::new(0.0, r1.y, r1.z))
            .to_degrees();
        let expect = 14.4 * f.rig.jaw.fraction(rest[chin]);
        assert!((ang - expect).abs() < 0.01, "{ang} vs {expect}");
        assert!(d[chin].y < rest[chin].y - 0.01);
        for (p, q) in rest.iter().zip(&d) {
            if p.y
                > f.mesh
                    .landmarks
                    .ear_lobe
                    .y
                    .max(f.mesh.landmarks.mouth_corner.y)
                || !f.rig.jaw.below_boundary(*p)
            {
                assert_eq!(p, q);
            }
        }
    }

    /// Mid upper-lid rise (m) of `emotion` held at full intensity, with
    /// the levator law set by `gain` and `max_raise`.
    fn mid_lid_rise(gain: f64, max_raise: Option<f64>, emotion: Emotion) -> f32 {
        let mut params = FaceParams::thesis_params();
        params.blink.levator_gain = gain;
        params.blink.levator_max_raise_m = max_raise;
        params.blink.mean_interval_s = 1e6;
        let f = Face::new(MeshParams { rows: 48 }, params);
        let mut s = FaceState::default();
        s.set_emotion(&f, emotion, 1.0, Speed::Fast, Pattern::III);
        let mut rng = StdRng::seed_from_u64(1);
        for _ in 0..2000 {
            s.step(&f, 0.001, &mut rng);
        }
        let mid = f.mesh.rims.upper_lid[0][f.mesh.rims.upper_lid[0].len() / 2] as usize;
        let mut out = vec![Vec3::ZERO; f.mesh.positions.len()];
        deform(&f, &s, &mut out);
        out[mid].y - f.mesh.positions[mid].y
    }

    /// Unbounded, the levator gain scales the lid's raise (a relaxation of
    /// the upper palpebral orbicularis, AU 5) and nothing else: surprise's
    /// mid-lid rises 2.5 times as far, anger's lowered lid is unchanged.
    #[test]
    fn levator_gain_scales_the_raise_only() {
        let (one, more) = (
            mid_lid_rise(1.0, None, Emotion::Surprise),
            mid_lid_rise(2.5, None, Emotion::Surprise),
        );
        assert!(one > 0.0005, "surprise raises the lid: {one}");
        assert!((more / one - 2.5).abs() < 0.05, "{one} -> {more}");
        let (one, more) = (
            mid_lid_rise(1.0, None, Emotion::Anger),
            mid_lid_rise(6.0, Some(0.0045), Emotion::Anger),
        );
        assert!(one < 0.0 && (one - more).abs() < 1e-6, "{one} vs {more}");
    }

    /// L1 bounded: the raise follows R tanh(g u / R) of the thesis lid's
    /// own raise u, so it never passes R however large the gain, and a
    /// larger relaxation still raises the lid further.
    #[test]
    fn levator_raise_saturates_below_its_bound() {
        let r = 0.0045;
        let u = mid_lid_rise(1.0, None, Emotion::Surprise);
        let bounded = mid_lid_rise(6.0, Some(r as f64), Emotion::Surprise);
        let expect = r * (6.0 * u / r).tanh();
        // The lid-clearance step may move the margin by a fraction of a mm.
        assert!((bounded - expect).abs() < 0.0003, "{bounded} vs {expect}");
        let huge = mid_lid_rise(1000.0, Some(r as f64), Emotion::Surprise);
        assert!(huge < r + 0.0003 && huge > bounded, "{huge}");
        let fear = mid_lid_rise(6.0, Some(r as f64), Emotion::Fear);
        assert!(0.0 < fear && fear < bounded, "{fear} vs {bounded}");
    }

    /// face.md section 4: a relaxed upper palpebral part raises the lid
    /// *showing white above the iris* in surprise and fear. At rest the
    /// lid covers the iris's top edge; with the default levator law the
    /// margin clears it by at least half a millimetre in both, at both
    /// mesh resolutions.
    #[test]
    fn surprise_and_fear_show_white_above_the_iris() {
        use shisen_gaze::anatomy::eye;
        let iris_top = (eye::RADIUS * eye::IRIS_DEG.to_radians().sin()) as f32;
        for rows in [32, 48, 100] {
            let mut params = FaceParams::default_params();
            params.blink.mean_interval_s = 1e6;
            let f = Face::new(MeshParams { rows }, params);
            let mid = f.mesh.rims.upper_lid[0][f.mesh.rims.upper_lid[0].len() / 2] as usize;
            let centre = f.rig.eye_centres[0].y;
            let rest = f.mesh.positions[mid].y - centre;
            assert!(
                rest < iris_top,
                "rows {rows}: the lid at rest covers the iris's top"
            );
            for emotion in [Emotion::Surprise, Emotion::Fear] {
                let mut s = FaceState::default();
                s.set_emotion(&f, emotion, 1.0, Speed::Fast, Pattern::III);
                let mut rng = StdRng::seed_from_u64(1);
                for _ in 0..2000 {
                    s.step(&f, 0.001, &mut rng);
                }
                let mut out = vec![Vec3::ZERO; f.mesh.positions.len()];
                deform(&f, &s, &mut out);
                let white = out[mid].y - centre - iris_top;
                println!("rows {rows} {emotion:?}: {:.2} mm of white", white * 1000.0);
                assert!(white > 0.0005, "rows {rows} {emotion:?}: {white} m");
            }
        }
    }

    /// Heights of the left eye's upper and lower mid margins in `emotion`
    /// at its apex, m.
    fn margins(f: &Face, emotion: Emotion) -> (f32, f32) {
        let mut s = FaceState::default();
        s.set_emotion(f, emotion, 1.0, Speed::Fast, Pattern::III);
        let mut rng = StdRng::seed_from_u64(1);
        for _ in 0..2000 {
            s.step(f, 0.001, &mut rng);
        }
        let mut out = vec![Vec3::ZERO; f.mesh.positions.len()];
        deform(f, &s, &mut out);
        let mid = |rim: &[u32]| out[rim[rim.len() / 2] as usize].y;
        (
            mid(&f.mesh.rims.upper_lid[0]),
            mid(&f.mesh.rims.lower_lid[0]),
        )
    }

    /// The eye's opening (upper minus lower mid margin), m.
    fn opening(f: &Face, emotion: Emotion) -> f32 {
        let (upper, lower) = margins(f, emotion);
        upper - lower
    }

    /// AU 7 (the lid tightener, 0.9 in anger's prototype) raises the
    /// lower lid by at least a millimetre and a half.
    #[test]
    fn anger_tightens_the_lower_lid() {
        let mut params = FaceParams::default_params();
        params.blink.mean_interval_s = 1e6;
        let f = Face::new(MeshParams { rows: 64 }, params);
        let rest = margins(&f, Emotion::Neutral).1;
        let rise = margins(&f, Emotion::Anger).1 - rest;
        println!("anger: lower lid up {:.2} mm", rise * 1e3);
        assert!(rise > 0.0015, "{rise}");
    }

    /// AU 6 narrows a smiling eye from below by a quarter to a half of
    /// its opening, the cheek's push on the lower lid adding at least a
    /// millimetre to what the sphincter's own field does.
    #[test]
    fn a_smile_narrows_the_eye_from_below() {
        let mut params = FaceParams::default_params();
        params.blink.mean_interval_s = 1e6;
        let f = Face::new(MeshParams { rows: 64 }, params.clone());
        let (neutral, smile) = (
            opening(&f, Emotion::Neutral),
            opening(&f, Emotion::Happiness),
        );
        println!(
            "opening: neutral {:.2} mm, smile {:.2} mm",
            neutral * 1e3,
            smile * 1e3
        );
        assert!(
            (0.5 * neutral..0.75 * neutral).contains(&smile),
            "{smile} vs {neutral}"
        );
        params.blink.cheek_lid_rise_m = 0.0;
        let seed = Face::new(MeshParams { rows: 64 }, params);
        let flat = opening(&seed, Emotion::Happiness);
        assert!(smile < flat - 0.001, "{smile} vs {flat} without the push");
    }

    #[test]
    fn state_blinks_in_neutral_and_follows_emotions() {
        let f = Face::new(MeshParams { rows: 32 }, FaceParams::thesis_params());
        let mut s = FaceState::default();
        let mut rng = StdRng::seed_from_u64(3);
        let mut closed = 0;
        for _ in 0..20_000 {
            s.step(&f, 0.001, &mut rng);
            let i = MuscleId {
                kind: MuscleKind::OculiUpperPalpebral,
                side: Side::Left,
            }
            .index()
            .unwrap();
            if (s.activation.k[i] - 2.9).abs() < 1e-3 {
                closed += 1;
            }
        }
        assert!(
            s.blink.count >= 1 && closed > 0,
            "blinks in 20 s of neutral"
        );
        s.set_emotion(&f, Emotion::Happiness, 1.0, Speed::Fast, Pattern::III);
        let before = s.blink.count;
        for _ in 0..20_000 {
            s.step(&f, 0.001, &mut rng);
        }
        assert!(s.blink.count > before, "people blink whatever they feel");
        // The thesis's rule, as an option: no spontaneous blinks out of neutral.
        let mut thesis = face(32);
        thesis.params.blink.neutral_only = true;
        let before = s.blink.count;
        for _ in 0..20_000 {
            s.step(&thesis, 0.001, &mut rng);
        }
        assert_eq!(
            s.blink.count, before,
            "no spontaneous blinks out of neutral"
        );
        assert!((s.activation.jaw_deg - 8.1).abs() < 1e-5);
        // Looking down lowers the lid (positive upper-palpebral contraction).
        s.set_emotion(&f, Emotion::Neutral, 0.0, Speed::Fast, Pattern::III);
        s.eye_pitch = [-0.3, -0.3];
        s.blink.potential = -1e9;
        s.step(&f, 2.0, &mut rng);
        let i = MuscleId {
            kind: MuscleKind::OculiUpperPalpebral,
            side: Side::Left,
        }
        .index()
        .unwrap();
        assert!(s.activation.k[i] > 0.0);
        // ... and the lower lid too (relaxed lower palpebral part, k < 0).
        let j = MuscleId {
            kind: MuscleKind::OculiLowerPalpebral,
            side: Side::Left,
        }
        .index()
        .unwrap();
        let lowered = s.activation.k[j] * f.rig.lid_y_per_k[0][1];
        let expect = 0.3 * dims::EYEBALL_R * (-0.3f32).sin();
        assert!(s.activation.k[j] < 0.0 && (lowered - expect).abs() < 1e-6);
    }
}
