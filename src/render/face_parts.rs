//! The face's separate parts, drawn with it: the mouth's inside (the dental
//! arches' crowns on the skull and the jaw, the oral cavity behind them)
//! and the eyelashes with the lids' margins, each placed on the deformed
//! face so they ride every expression, jaw movement and blink.

use glam::{Mat4, Quat, Vec3};

use shisen::sim::Sim;

use super::draw::{Draw, Material, MeshKey};
use super::geometry::Vertex;

/// Inside of the mouth, and teeth.
const MOUTH: [f32; 4] = {
    let c = shisen_face::appearance::FaceStyle::DEFAULT.inside;
    [c[0], c[1], c[2], 1.0]
};

/// The mouth's inside, seen when the lips part: a dark cavity behind the
/// lips, placed from the middle of the lips' deformed edges, and the teeth,
/// fixed to the bones: the upper incisors to the skull, the lower ones to
/// the jaw, turning with it (F7), all in the face frame `face_frame`. The
/// lips move over the teeth: a raised upper lip bares the upper teeth, a
/// lowered lower lip the lower ones. Teeth are drawn only when the lips
/// are apart (closed lips hide them; drawn, they would show through the
/// seam).
///
/// A head without lip rims (an imported mesh whose mouth is not cut
/// open) has no opening to see into: nothing is drawn.
pub(super) fn mouth(sim: &Sim, face: &[Vertex], face_frame: Mat4) -> Vec<Draw> {
    let model = &sim.model().face;
    let (mesh, l) = (&model.mesh, &model.mesh.landmarks);
    let mid = |rim: &[u32]| Some(*rim.get(rim.len() / 2)? as usize);
    let (Some(ui), Some(li)) = (mid(&mesh.rims.upper_lip), mid(&mesh.rims.lower_lip)) else {
        return Vec::new();
    };
    let (upper, lower) = (
        Vec3::from_array(face[ui].pos),
        Vec3::from_array(face[li].pos),
    );
    let gap = upper.distance(lower);
    let w = l.mouth_corner.x;
    let ellipsoid = |centre: Vec3, half: Vec3, color| Draw {
        mesh: MeshKey::Sphere,
        model: face_frame * Mat4::from_scale_rotation_translation(half, Quat::IDENTITY, centre),
        color,
        material: Material::Plain,
    };
    // The cavity is dark and reaches past the mouth's corners, which lie
    // well behind its middle, so the neck inside the head never shows
    // through the opening; with the teeth showing, its front stands behind
    // the canines and is deep, so its surface curves back behind the
    // premolars at the corners (the head's inside between is drawn dark,
    // shader.wgsl). Behind closed lips it only darkens the seam and stays within the
    // mouth's width: that close to the lips a wider one would come out
    // through the cheeks beside the corners.
    let cavity = |front: f32, reach: f32, half_d: f32| {
        ellipsoid(
            Vec3::new(0.0, (upper.y + lower.y) / 2.0, front - half_d),
            Vec3::new(w * reach, 0.02 + gap * 0.6, half_d),
            MOUTH,
        )
    };
    // The buccal corridors: the dark space between the back teeth and the
    // cheeks, which a wide mouth shows at its corners (and a closed one's
    // seam at its ends). A shaded blob behind each deformed corner, short
    // of the cheek's skin beside it, hides what stands inside the head
    // there.
    let end_on = |rim: &[u32], side: f32| {
        [rim[0], rim[rim.len() - 1]]
            .map(|i| Vec3::from_array(face[i as usize].pos))
            .into_iter()
            .find(|p| p.x.signum() == side)
    };
    let mut corridors = Vec::new();
    for side in [-1.0f32, 1.0] {
        let (Some(a), Some(b)) = (
            end_on(&mesh.rims.upper_lip, side),
            end_on(&mesh.rims.lower_lip, side),
        ) else {
            continue;
        };
        let corner = (a + b) / 2.0;
        let centre = corner + Vec3::new(-side * 0.004, 0.0, -CORRIDOR_HALF[2]);
        let half = Vec3::new(
            CORRIDOR_HALF[0],
            CORRIDOR_HALF[1] + gap * 0.3,
            CORRIDOR_HALF[2],
        );
        corridors.push(ellipsoid(centre, half, MOUTH));
    }
    let lips_back = upper.z.min(lower.z) - 0.006;
    if gap < TEETH_SHOW_GAP {
        corridors.push(cavity(lips_back, 1.0, 0.026));
        return corridors;
    }
    // Incisal edges at rest: the upper one a little below the upper lip's
    // rest edge and behind it; the lower one overlapped by the upper
    // (overbite) and behind it (overjet).
    let rest_lip = mesh.positions[ui];
    let upper_edge = Vec3::new(0.0, rest_lip.y - INCISOR_SHOW, rest_lip.z - INCISOR_DEPTH);
    let lower_rest = upper_edge + Vec3::new(0.0, OVERBITE, -OVERJET);
    let jaw = &model.rig.jaw;
    let theta = sim.face_state.activation.jaw_deg.to_radians();
    let lower_edge = lower_rest + shisen_face::muscle::jaw_rotation(lower_rest - jaw.pivot, theta);
    // Lips bunched in front of the teeth (a tightened mouth pulls the skin
    // above and below the lips over them) must still cover them: each
    // arch goes back behind the nearest skin in front of its crowns, if it
    // is nearer than their place on the bones (the surface has no lip
    // thickness). Each arch looks only at the skin level with its own
    // crowns: a lower lip carried down and back by the jaw lies under the
    // upper teeth, not in front of them.
    let half_w = w * 0.62;
    let (upper_band, lower_band) = (
        upper_edge.y - 0.001..upper_edge.y + 0.01,
        lower_edge.y - 0.01..lower_edge.y + 0.001,
    );
    // The nearest skin level with each arch's crowns, in one pass.
    let (upper_skin, lower_skin) = face
        .iter()
        .map(|v| Vec3::from_array(v.pos))
        .filter(|p| p.x.abs() < half_w && p.z > rest_lip.z - LIP_REACH)
        .fold((f32::INFINITY, f32::INFINITY), |(u, l), p| {
            (
                if upper_band.contains(&p.y) {
                    u.min(p.z)
                } else {
                    u
                },
                if lower_band.contains(&p.y) {
                    l.min(p.z)
                } else {
                    l
                },
            )
        });
    let push_upper = (upper_edge.z - (upper_skin - 0.001)).max(0.0);
    let push_lower = (lower_edge.z - (lower_skin - 0.001)).max(0.0);
    // Light reaches teeth behind the lips only through the opening: the
    // open fraction of their view out of a slit of width `gap` at the
    // lips' depth `d` is about g / (g + 2 d); scaled so a wide-open mouth
    // is fully lit.
    let lit = (1.2 * gap / (gap + 2.0 * INCISOR_DEPTH)).clamp(0.45, 1.0);
    // The cavity stands behind the upper canines and behind the lower
    // ones, which the jaw carries back as it opens (about 6 mm behind the
    // lower incisors round their smaller arch).
    let front =
        (upper_edge.z - CAVITY_BEHIND_TEETH - push_upper).min(lower_edge.z - 0.007 - push_lower);
    let mut draws = corridors;
    draws.push(cavity(lips_back.min(front), 1.3, 0.045));
    let shaded = |c: [f32; 3], shade: f32| [c[0] * shade, c[1] * shade, c[2] * shade, 1.0];
    // The tongue lies on the mouth's floor behind the lower incisors, its
    // back under the palate, and drops with the jaw; the part behind the
    // cavity's front is hidden by it.
    let tongue_rest = lower_rest + Vec3::new(0.0, -TONGUE_HALF[1] + 0.001, -TONGUE_HALF[2] - 0.004);
    draws.push(Draw {
        mesh: MeshKey::Blob,
        model: face_frame
            * Mat4::from_scale_rotation_translation(
                Vec3::from_array(TONGUE_HALF),
                Quat::from_rotation_x(theta),
                tongue_rest + shisen_face::muscle::jaw_rotation(tongue_rest - jaw.pivot, theta)
                    - Vec3::Z * push_lower,
            ),
        color: shaded(TONGUE, lit),
        material: Material::Plain,
    });
    // Each arch's teeth, midline outward, along the arch's curve (the
    // lower one turning with the jaw), each crown facing out of the arch,
    // and the gum over its neck.
    let arches = [
        (upper_edge, &UPPER_TEETH, &UPPER_ARCH, 1.0, 0.0, push_upper),
        (
            lower_rest,
            &LOWER_TEETH,
            &LOWER_ARCH,
            -1.0,
            theta,
            push_lower,
        ),
    ];
    for (edge, teeth, arch, up, turn, push) in arches {
        let mut s = 0.0;
        for (k, &(width, height)) in teeth.iter().enumerate() {
            let (x, back, angle) = arch_at(arch, s + width / 2.0);
            s += width;
            // Teeth further round the arch sit deeper in the mouth's shade.
            let shade = lit * (1.0 - back / 0.05).clamp(0.5, 1.0);
            for side in [-1.0f32, 1.0] {
                let rotation = Quat::from_rotation_x(turn) * Quat::from_rotation_y(side * angle);
                let inward = rotation * -Vec3::Z;
                let place = |y: f32, depth: f32| {
                    let root = edge + Vec3::new(side * x, y, -back);
                    root + shisen_face::muscle::jaw_rotation(root - jaw.pivot, turn)
                        + inward * depth
                        - Vec3::Z * push
                };
                // A crown is a flat-fronted, rounded block; the narrow
                // gaps between them show the cavity as the lines between
                // teeth, and the gum's papillae at their necks.
                let block = |centre: Vec3, half: Vec3, color| Draw {
                    mesh: MeshKey::Tooth,
                    model: face_frame
                        * Mat4::from_scale_rotation_translation(half, rotation, centre),
                    color,
                    material: Material::Plain,
                };
                // Each tooth a little different in shade (the canines
                // yellower and darker, as they are).
                let tint = TOOTH_TINT[k.min(TOOTH_TINT.len() - 1)];
                let [r, g, b, _] = shaded(TEETH, shade * tint[0]);
                draws.push(Draw {
                    material: Material::Tooth,
                    ..block(
                        place(up * height / 2.0, TOOTH_HALF_DEPTH),
                        Vec3::new(width * 0.46, height / 2.0, TOOTH_HALF_DEPTH),
                        [r, g * tint[1], b * tint[2], -up],
                    )
                });
                draws.push(block(
                    place(
                        up * (height + GUM_HEIGHT / 2.0 - GUM_OVER),
                        1.4 * TOOTH_HALF_DEPTH,
                    ),
                    Vec3::new(width * 0.56, GUM_HEIGHT / 2.0, TOOTH_HALF_DEPTH),
                    shaded(GUM, shade),
                ));
            }
        }
    }
    draws
}

/// The place `s` metres along one side of a dental arch from the midline
/// (a polyline such as [`UPPER_ARCH`], extended past its last point):
/// across and back from the incisal midpoint, m, and the angle of the
/// arch's outward normal from straight ahead.
fn arch_at(arch: &[[f32; 2]], s: f32) -> (f32, f32, f32) {
    let mut left = s;
    let last = arch.len() - 2;
    for (i, w) in arch.windows(2).enumerate() {
        let d = glam::Vec2::from(w[1]) - glam::Vec2::from(w[0]);
        let len = d.length();
        if left <= len || i == last {
            let p = glam::Vec2::from(w[0]) + d * (left / len);
            return (p.x, p.y, d.y.atan2(d.x));
        }
        left -= len;
    }
    (0.0, 0.0, 0.0)
}

/// Crown colours (linear RGB): enamel, a little darker and yellower than
/// white; the attached gingiva's pink; the tongue's red.
const TEETH: [f32; 3] = [0.84, 0.77, 0.68];
const GUM: [f32; 3] = [0.52, 0.17, 0.17];
const TONGUE: [f32; 3] = [0.46, 0.13, 0.13];
/// Each tooth's shade from the midline out (brightness, then green and
/// blue against red): the canines are darker and yellower than the
/// incisors beside them (their enamel is thicker over darker dentine), the
/// premolars between (our reading of shade guides).
const TOOTH_TINT: [[f32; 3]; 6] = [
    [1.0, 1.0, 1.0],
    [0.97, 0.99, 0.98],
    [0.90, 0.95, 0.88],
    [0.94, 0.98, 0.95],
    [0.93, 0.98, 0.95],
    [0.90, 0.97, 0.93],
];

/// Half sizes of the tongue's resting body (across, up, back), m: an adult
/// tongue is about 5 cm across and 7-10 cm long (our reading; only its tip
/// and the top of its blade show).
const TONGUE_HALF: [f32; 3] = [0.023, 0.008, 0.032];
/// Gum shown over a crown's neck, and how far the crown overlaps it, m
/// (the attached gingiva is 3-6 mm high; a smile that lifts the upper lip
/// 2-3 mm past the crowns shows it).
const GUM_HEIGHT: f32 = 0.006;
const GUM_OVER: f32 = 0.0015;

/// Crown width (along the arch) and height of each tooth from the midline
/// out to the first molar, m (Wheeler's mean crown dimensions: Nelson
/// 2015, Wheeler's Dental Anatomy, 10th ed.). Only what the lips' opening
/// frames is seen: the premolars and the first molar fill a wide smile's
/// corners.
const UPPER_TEETH: [(f32, f32); 6] = [
    (0.0085, 0.0105),
    (0.0065, 0.0090),
    (0.0075, 0.0100),
    (0.0070, 0.0085),
    (0.0065, 0.0080),
    (0.0100, 0.0075),
];
const LOWER_TEETH: [(f32, f32); 6] = [
    (0.0050, 0.0090),
    (0.0055, 0.0095),
    (0.0070, 0.0110),
    (0.0070, 0.0085),
    (0.0070, 0.0080),
    (0.0110, 0.0075),
];
/// Each arch's curve, one side, from the incisal midpoint: points across
/// and back, m. It rounds through the incisors to the canine's tip (the
/// arch's corner: intercanine width about 34 mm upper, 26 mm lower, 9 and
/// 6 mm behind the incisors) and runs back and out along the premolars to
/// the first molars (intermolar width about 50 and 45 mm, 27 and 24 mm
/// back): Bishara et al. 1997, Am. J. Orthod. 111:401.
const UPPER_ARCH: [[f32; 2]; 6] = [
    [0.0, 0.0],
    [0.0060, 0.0011],
    [0.0115, 0.0041],
    [0.0170, 0.0090],
    [0.0210, 0.0180],
    [0.0260, 0.0360],
];
const LOWER_ARCH: [[f32; 2]; 6] = [
    [0.0, 0.0],
    [0.0045, 0.0006],
    [0.0090, 0.0024],
    [0.0130, 0.0060],
    [0.0175, 0.0150],
    [0.0230, 0.0330],
];
/// Half the thickness drawn of a crown, front to back, m (our choice:
/// only the front face shows).
const TOOTH_HALF_DEPTH: f32 = 0.003;

/// How far the cavity's front stands behind the upper incisors' when the
/// teeth show, m: behind the canines' crowns (about 8 mm back round the
/// arch, 6 mm thick), so the upper front teeth are all seen.
const CAVITY_BEHIND_TEETH: f32 = 0.014;

/// How far the upper incisors reach below the upper lip's rest edge, m:
/// about 2 mm in young men with the lips apart at rest (Vig & Brundo 1978,
/// J. Prosthet. Dent. 39:502: 1-3.5 mm, more in women and the young).
const INCISOR_SHOW: f32 = 0.002;

/// How far the upper incisors' front sits behind the upper lip's edge, m
/// (the lip's thickness at its edge; our choice).
const INCISOR_DEPTH: f32 = 0.004;

/// Vertical overlap and horizontal step of the lower incisors behind the
/// upper ones in a closed bite, m: the orthodontic norm of about 2 mm each.
const OVERBITE: f32 = 0.002;
const OVERJET: f32 = 0.0025;

/// Skin up to this far behind the upper lip's rest edge can lie in front
/// of the teeth (the lips and the skin around them), m.
const LIP_REACH: f32 = 0.015;

/// Half sizes of the dark blob in each corner of an open mouth (across,
/// up, deep), m (our choice: inside the corner, behind the premolars).
const CORRIDOR_HALF: [f32; 3] = [0.006, 0.004, 0.007];

/// Lips further apart than this show the teeth, m.
const TEETH_SHOW_GAP: f32 = 0.003;

/// The caruncles: a small, moist, pink mound in each eye's inner corner,
/// on the deformed lids' meeting point, a little behind it and toward
/// the eye, in the face frame.
pub(super) fn caruncles(
    rims: &shisen_face::mesh::Rims,
    face: &[Vertex],
    face_frame: Mat4,
) -> Vec<Draw> {
    rims.upper_lid
        .iter()
        .zip(&rims.lower_lid)
        .filter(|(u, l)| !u.is_empty() && !l.is_empty())
        .map(|(upper, lower)| {
            // A rim's end nearer the midline.
            let inner = |rim: &[u32]| {
                [rim[0], rim[rim.len() - 1]]
                    .map(|i| Vec3::from_array(face[i as usize].pos))
                    .into_iter()
                    .min_by(|a, b| a.x.abs().total_cmp(&b.x.abs()))
                    .expect("two ends")
            };
            let corner = (inner(upper) + inner(lower)) / 2.0;
            let toward_eye = Vec3::X * corner.x.signum() * CARUNCLE_HALF[0];
            Draw {
                mesh: MeshKey::Blob,
                model: face_frame
                    * Mat4::from_scale_rotation_translation(
                        Vec3::from_array(CARUNCLE_HALF),
                        Quat::IDENTITY,
                        corner + toward_eye - Vec3::Z * (1.5 * CARUNCLE_HALF[2]),
                    ),
                color: CARUNCLE,
                material: Material::Plain,
            }
        })
        .collect()
}

/// The upper lids' shadow on the eyes: each eye's draw (material `Eye`)
/// is given, in its colour's red and green, the height of its upper lid's
/// margin in the eyeball's own unit frame (local y, +1 at the top) at the
/// margin's middle and at its ends (the corners), so the shader can shade
/// the band of eyeball just under the lid, which its lashes and the lid's
/// rim hide from the light above. The lid rides the eye's pitch and the
/// expression (AU 5 lifts it, a blink lowers it), and the shadow with it.
/// The rim nearest each eye is its own.
pub(super) fn lid_shadows(
    rims: &shisen_face::mesh::Rims,
    face: &[Vertex],
    face_frame: Mat4,
    draws: &mut [Draw],
) {
    for d in draws.iter_mut().filter(|d| d.material == Material::Eye) {
        let centre = d.model.transform_point3(Vec3::ZERO);
        let to_local = d.model.inverse() * face_frame;
        let local = |i: u32| to_local.transform_point3(Vec3::from_array(face[i as usize].pos));
        let nearest = rims
            .upper_lid
            .iter()
            .filter(|r| r.len() >= 3)
            .min_by(|a, b| {
                let dist = |r: &[u32]| {
                    face_frame
                        .transform_point3(Vec3::from_array(face[r[r.len() / 2] as usize].pos))
                        .distance(centre)
                };
                dist(a).total_cmp(&dist(b))
            });
        let Some(rim) = nearest else { continue };
        let mid = local(rim[rim.len() / 2]).y;
        let ends = (local(rim[0]).y + local(rim[rim.len() - 1]).y) / 2.0;
        d.color = [mid, ends, 0.0, 1.0];
    }
}

/// Half sizes of a caruncle (across, up, deep), m: about 2 by 3 mm of it
/// shows (our reading of anatomy atlases), and its colour.
const CARUNCLE_HALF: [f32; 3] = [0.0011, 0.0016, 0.0010];
const CARUNCLE: [f32; 4] = [0.52, 0.31, 0.29, 1.0];

/// Lashes, m: upper and lower length at mid-lid (Thibaut et al. 2010,
/// Br. J. Dermatol. 163:1023: upper 8-12 mm, lower 6-8 mm; shorter here,
/// seen curled).
const LASH_LENGTH: [f32; 2] = [0.006, 0.0018];
/// Thickness of the lid at its margin, m (our choice: a thin ledge that
/// reads as the lid's edge).
const LID_THICKNESS: f32 = 0.0018;
/// The tear meniscus: the share of the lower lid's ledge it covers from
/// the eyeball out (about 0.3 mm of the 1.8 mm margin: the meniscus is
/// 0.2-0.3 mm high, Holly 1985), and its colour, the margin's seen
/// through a wet film that reflects the room.
const TEAR_LINE: f32 = 0.2;
const TEAR: [f32; 4] = [0.95, 0.80, 0.78, 1.0];
/// The lid margin's moist, pinker skin.
const LID_MARGIN: [f32; 4] = [0.55, 0.30, 0.27, 1.0];
const LASH: [f32; 4] = {
    let l = shisen_face::appearance::FaceStyle::DEFAULT.lashes;
    [l[0], l[1], l[2], 1.0]
};

/// Lashes along each lid, spaced this far apart at the root, m (people
/// have 90-160 upper and 70-80 lower lashes in several rows; one row of
/// strands this close, each a fraction of a pixel wide at sparring
/// distance, reads as the same soft dark fringe).
const LASH_SPACING: f32 = 0.0006;
/// Width of a lash at its root, m (a lash is about 0.1 mm thick; drawn
/// wider, as several lashes of a row overlap).
const LASH_WIDTH: f32 = 0.0005;
/// Straight pieces a lash's curve is drawn with.
const LASH_SEGMENTS: usize = 2;
/// Depth of the upper lashes' dense roots along the lid's edge, m (our
/// choice: about a millimetre, where the lashes stand in two or three rows,
/// and the lid's edge reads dark in any light).
const LASH_ROOT: f32 = 0.0013;

/// Eyelashes and lid margins: a curled fringe of thin tapered strands on
/// each lid rim and a narrow ledge behind it (the lid's thickness), rooted
/// on the deformed rim so they ride every lid movement and blink. The
/// strands are spaced along the rim's length, not per mesh vertex, so the
/// fringe is as dense at every mesh resolution; each strand's length and
/// lean vary a little (a fixed pattern, no randomness), the outer ones
/// lean out towards the eye's corner. The upper fringe sweeps forward and
/// up, the lower forward and down; both taper to nothing at the corners.
/// A triangle list, face frame.
pub(super) fn lashes(rims: &shisen_face::mesh::Rims, face: &[Vertex]) -> Vec<Vertex> {
    let mut out = Vec::new();
    let vertex = |i: u32| {
        let v = &face[i as usize];
        (Vec3::from_array(v.pos), Vec3::from_array(v.normal))
    };
    for (rim, len, lift) in rims
        .upper_lid
        .iter()
        .map(|r| (r, LASH_LENGTH[0], 1.0))
        .chain(rims.lower_lid.iter().map(|r| (r, LASH_LENGTH[1], -1.0)))
    {
        let n = rim.len();
        if n < 2 {
            continue;
        }
        // The lid's margin: a ledge from the rim back toward the eyeball,
        // the lid's thickness, seen from below (upper lid) or above.
        let ledge = |i: usize| {
            let (p, nrm) = vertex(rim[i]);
            [p, p - nrm * LID_THICKNESS]
        };
        for i in 0..n - 1 {
            let (a, b) = (ledge(i), ledge(i + 1));
            let quad = [a[0], b[0], b[1], a[0], b[1], a[1]];
            let normal = Vec3::Y * -lift;
            out.extend(quad.map(|p| Vertex::coloured(p, normal, LID_MARGIN)));
            // The tear film's meniscus along the lower lid's inner edge,
            // against the eyeball: a thin wet line catching the light.
            if lift < 0.0 {
                let inner = |e: [Vec3; 2]| [e[1].lerp(e[0], TEAR_LINE), e[1]];
                let (a, b) = (inner(a), inner(b));
                let quad = [a[0], b[0], b[1], a[0], b[1], a[1]];
                let lifted = quad.map(|p| p + Vec3::Y * 0.00005);
                out.extend(lifted.map(|p| Vertex::coloured(p, Vec3::Y, TEAR)));
            }
        }
        // Arc length along the deformed rim.
        let mut at = vec![0.0f32; n];
        for i in 1..n {
            at[i] = at[i - 1] + vertex(rim[i]).0.distance(vertex(rim[i - 1]).0);
        }
        let total = at[n - 1];
        // The upper lashes' roots: dense enough to read as one dark line
        // along the lid's edge (what the eye's outline is at a distance),
        // thinning to the corners.
        if lift > 0.0 {
            let band = |i: usize| {
                let (p, nrm) = vertex(rim[i]);
                let xi = 2.0 * at[i] / total.max(1e-9) - 1.0;
                let out_dir = (nrm + Vec3::Z).normalize_or(Vec3::Z);
                let width = LASH_ROOT * (1.0 - xi * xi).max(0.0).sqrt().sqrt();
                [p, p + (out_dir + Vec3::Y).normalize_or(Vec3::Y) * width]
            };
            for i in 0..n - 1 {
                let (a, b) = (band(i), band(i + 1));
                let quad = [a[0], b[0], b[1], a[0], b[1], a[1]];
                let normal = (b[0] - a[0]).cross(a[1] - a[0]).normalize_or(Vec3::Z);
                out.extend(quad.map(|p| Vertex::coloured(p, normal, LASH)));
            }
        }
        let outer_last = vertex(rim[n - 1]).0.x.abs() > vertex(rim[0]).0.x.abs();
        let count = (total / LASH_SPACING) as usize;
        let mut seg = 0;
        for k in 0..count {
            let s = (k as f32 + 0.5) / count as f32 * total;
            while seg + 2 < n && at[seg + 1] < s {
                seg += 1;
            }
            let f = ((s - at[seg]) / (at[seg + 1] - at[seg]).max(1e-9)).clamp(0.0, 1.0);
            let ((p0, n0), (p1, n1)) = (vertex(rim[seg]), vertex(rim[seg + 1]));
            let root = p0.lerp(p1, f);
            let along = (p1 - p0).normalize_or(Vec3::X);
            let nrm = n0.lerp(n1, f);
            // xi in [-1, 1] from one corner to the other; `outer` is +1 at
            // the outer corner (the rim end farther from the midline).
            let xi = 2.0 * s / total - 1.0;
            let outer = if outer_last { xi } else { -xi };
            let outward = if outer_last { along } else { -along };
            // A fixed, irregular pattern of length and lean.
            let jitter = |m: f32| (k as f32 * m).sin();
            let l = len * (1.0 - xi * xi).max(0.0).sqrt() * (0.8 + 0.2 * jitter(12.9898));
            if l <= 0.0 {
                continue;
            }
            let lean = outward * (0.25 * outer.max(0.0) + 0.18 * jitter(78.233));
            let out_dir = (nrm + Vec3::Z).normalize_or(Vec3::Z);
            // A fine strand curling away from the lid: out along the lid's
            // normal, then more and more up (down for the lower lid), and
            // tapering from its root to a point.
            let at = |f: f32| {
                root + (out_dir * 0.75 + lean) * (l * f) + Vec3::Y * (lift * l * 0.65 * f * f)
            };
            let w = along * (0.5 * LASH_WIDTH);
            let segments = LASH_SEGMENTS as f32;
            for j in 0..LASH_SEGMENTS {
                let (f0, f1) = (j as f32 / segments, (j + 1) as f32 / segments);
                let (a, b) = (at(f0), at(f1));
                let (wa, wb) = (w * (1.0 - f0), w * (1.0 - f1));
                let quad = [a - wa, a + wa, b + wb, a - wa, b + wb, b - wb];
                let normal = (a + wa - (a - wa)).cross(b - a).normalize_or(Vec3::Z);
                out.extend(quad.map(|p| Vertex::coloured(p, normal, LASH)));
            }
        }
    }
    out
}

/// Depth of a short crop's hair standing off the scalp, m (our choice for
/// hair 1-2 cm long lying back: about 6 mm), reached this far above the
/// hairline, where the hairs grow out of the skin lying flat.
const HAIR_DEPTH: f32 = 0.006;
const HAIR_RISE: f32 = 0.014;
/// The shell stands at least this far off the skin, m, so the two never
/// fight for a pixel's depth where it meets the hairline.
const HAIR_LIFT: f32 = 0.0003;
/// How far single hairs stray below the hairline's smooth course, m (the
/// shader's wobble, `fs_scalp`).
const HAIRLINE_WOBBLE: f32 = 0.002;
const HAIR: [f32; 4] = {
    let h = shisen_face::appearance::FaceStyle::DEFAULT.hair;
    [h[0], h[1], h[2], 1.0]
};

/// The hair as a shell over the scalp: the face's vertices lifted off the
/// deformed skin along their normals by the hair's depth, which grows from
/// nothing at the hairline (the shell meets the skin there, whose painted
/// hair carries on under it) to [`HAIR_DEPTH`], and the face's triangles
/// that reach the hairline or lie above it. It gives the head its
/// silhouette of hair and a surface whose strands catch the light. One
/// lifted vertex per face vertex (the vertex colour's alpha carries its
/// height above the hairline, m, where the shader cuts the shell) and
/// the indices into them of the triangles of each of the face's `levels`
/// of detail (the fine one and the middle one), face frame; the indices
/// depend on the rest paint only, so they are the same every frame.
pub(super) fn hair_shell(
    levels: [&[[u32; 3]]; 2],
    face: &[Vertex],
) -> (Vec<Vertex>, [Vec<u32>; 2]) {
    let height = |v: &Vertex| shisen_face::appearance::hair_height(&v.paint);
    let lifted = face
        .iter()
        .map(|v| {
            let h = height(v);
            let t = (h / HAIR_RISE).clamp(0.0, 1.0);
            let depth = HAIR_LIFT + HAIR_DEPTH * t * (2.0 - t);
            let (p, n) = (Vec3::from_array(v.pos), Vec3::from_array(v.normal));
            Vertex::coloured(p + n * depth, n, [HAIR[0], HAIR[1], HAIR[2], h])
        })
        .collect();
    let indices = levels.map(|triangles| {
        triangles
            .iter()
            .filter(|t| {
                t.iter()
                    .any(|&i| height(&face[i as usize]) >= -HAIRLINE_WOBBLE)
            })
            .flatten()
            .copied()
            .collect()
    });
    (lifted, indices)
}
