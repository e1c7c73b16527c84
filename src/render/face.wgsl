// The head's own materials (the face, the eyes): a part of shader.wgsl,
// kept apart so each file reads in one sitting; the renderer joins them
// into one module (WGSL declarations may come in any order).

// Eye: PUPIL_COS, LIMBUS_COS and IRIS_COS, the cosines of the angular radii
// of the pupil, the iris's stroma and its limbal ring seen from the eyeball
// centre, are prepended by the renderer from `anatomy::eye`.

fn eye_colour(local: vec3<f32>) -> vec3<f32> {
    let d = normalize(local);
    let c = d.z;
    if (c > PUPIL_COS) {
        return vec3<f32>(0.005, 0.005, 0.008);
    }
    if (c > LIMBUS_COS) {
        // The stroma: grey-blue, darker toward the limbus, with a warmer
        // collarette round the pupil (a light iris's usual central ring),
        // irregular radial fibres and darker crypts between them (our
        // reading of iris photographs; a saturated, even blue reads as
        // glass).
        let a = atan2(d.y, d.x);
        let t = (c - LIMBUS_COS) / (PUPIL_COS - LIMBUS_COS);
        let fibre = 0.8 + 0.2 * sin(a * 29.0 + 2.0 * sin(a * 7.0 + t * 9.0));
        let crypt = hash2(vec2<f32>(floor(a * 9.0), floor(t * 4.0)));
        let pit = 1.0 - 0.3 * smoothstep(0.75, 0.95, crypt) * sin(3.1415927 * fract(t * 4.0));
        let stroma = mix(vec3<f32>(0.07, 0.10, 0.13), vec3<f32>(0.20, 0.28, 0.34), smoothstep(0.0, 0.5, t));
        let collarette = vec3<f32>(0.20, 0.15, 0.09);
        return mix(stroma, collarette, smoothstep(0.62, 0.85, t)) * fibre * pit;
    }
    if (c > IRIS_COS) {
        return vec3<f32>(0.05, 0.07, 0.10); // limbal ring
    }
    // Sclera: white by the iris, greyer and pinker toward the eye's
    // corners, where it curves away under the lids' shade and shows its
    // vessels (our choice; a uniform white reads as a painted disc).
    let t = clamp((IRIS_COS - c) / (IRIS_COS - 0.45), 0.0, 1.0);
    var white = mix(vec3<f32>(0.78, 0.75, 0.70), vec3<f32>(0.70, 0.57, 0.54), t * t);
    // Fine vessels, more toward the corners: two crossing wavy families.
    let a = atan2(d.y, d.x);
    let w1 = max(sin(a * 11.0 + c * 23.0) * sin(a * 7.0 - c * 31.0), 0.0);
    let w2 = w1 * w1;
    let vein = (w2 * w2) * (w2 * w2) * t;
    white = mix(white, vec3<f32>(0.62, 0.25, 0.22), 0.45 * vein);
    return white;
}


// Signed distance of a point of the face (rest x, y; its present depth
// z, within a few millimetres of its rest depth on the lips) inside the
// lips' colour, m: LipShape::inside in face/appearance.rs, whose numbers
// are prepended to this file.
fn lips_inside(rest: vec2<f32>, z: f32) -> f32 {
    let half_w = g.lips[0].x;
    let mouth_y = g.lips[0].y;
    let u = min(abs(rest.x) / half_w, 1.0);
    let taper = pow(max(1.0 - u * u, 1e-6), LIP_TAPER);
    let b = (u - LIP_BOW.y) / LIP_BOW.z;
    let d = u / LIP_DIP.y;
    let bow = 1.0 + LIP_BOW.x * exp(-b * b) - LIP_DIP.x * exp(-d * d);
    let top = mouth_y + g.lips[0].z * taper * bow;
    let bottom = mouth_y - g.lips[0].w * taper;
    let band = min(min(top - rest.y, rest.y - bottom), min(half_w - abs(rest.x), z - g.lips[1].x));
    let to_line = length(vec2<f32>(max(abs(rest.x) - half_w, 0.0), rest.y - mouth_y));
    return max(band, min(MOUTH_EDGE - to_line, z - g.lips[1].x));
}

// The buckled skin's profile over one line (docs/model/face.md W5). A
// gentle squeeze buckles the skin into W2's sinusoid, height cos(t) of
// the phase angle t; a stronger one localises into folds (the
// wrinkle-to-fold transition of a compressed sheet on a soft
// foundation, Pocivavsek et al. 2008, Science 320:912): rounded ridges
// between sharp creases, height 2 |cos(t / 2)| - 1, and some lines
// deeper than their neighbours. `fold` (0-1) is how far the squeeze has
// gone from one to the other: it grows with W2's peak slope up to
// FOLD_SLOPE (our choice).
const FOLD_SLOPE: f32 = 1.0;
// How much deeper or shallower a line may be than the mean in full folds
// (our choice: a raised forehead shows two or three strong lines among
// fainter ones).
const FOLD_SPREAD: f32 = 0.8;
// Shadow at a furrow's floor: the sinusoid's broad one, the fold's
// crease (our choices; their means over a line, which a far-away face
// keeps, are both 0.12: a fold is a thinner, darker line, not a lighter
// brow).
const FURROW_WAVE: f32 = 0.33;
const FURROW_CREASE: f32 = 0.75;

fn fold_of(slope: f32) -> f32 {
    return clamp(slope / FOLD_SLOPE, 0.0, 1.0);
}

// The normal's tilt along the axis at phase `p` (in lines), per unit of
// W2's peak slope: minus the profile's derivative, peaking at 1 for both
// profiles; a line's depth varies in folds (by its index).
fn fold_tilt(p: f32, fold: f32, family: f32) -> f32 {
    let t = 6.2831853 * fract(p);
    let wave = sin(t);
    let crease = select(-1.0, 1.0, t < 3.1415927) * sin(0.5 * t);
    let depth = 1.0 + fold * FOLD_SPREAD * (hash2(vec2<f32>(floor(p), family)) - 0.5);
    return mix(wave, crease, fold) * depth;
}

// The furrow's shadow at phase `p`: the sinusoid's ((1 - cos t) / 2)^2,
// the crease's (1 - |cos(t / 2)|)^3.
fn fold_furrow(p: f32, fold: f32) -> f32 {
    let t = 6.2831853 * fract(p);
    let s = 0.5 * (1.0 - cos(t));
    let d = 1.0 - abs(cos(0.5 * t));
    return mix(FURROW_WAVE * s * s, FURROW_CREASE * d * d * d, fold);
}

// Its mean over a line (0.375 and 0.166 of the two profiles' floors).
fn fold_furrow_mean(fold: f32) -> f32 {
    return mix(FURROW_WAVE * 0.375, FURROW_CREASE * 0.166, fold);
}

// Stubble: the cut hairs of a shaved beard, dark dots at the hairs'
// spacing (beard density about 60 hairs per cm2 on the chin and upper
// lip: Tolgyesi et al. 1983, J. Soc. Cosmet. Chem. 34:361, so 1.3 mm
// apart), each the hair's dark root seen through the skin (about 0.3 mm
// across). Where the dots are finer than a pixel they fade into their
// mean cover.
const STUBBLE_CELL: f32 = 0.0013;
const STUBBLE_R: f32 = 0.12;
fn stubble_dots(q: vec2<f32>) -> f32 {
    let u = q / STUBBLE_CELL;
    let fw = max(fwidth(u.x), fwidth(u.y));
    let c = floor(u);
    let jitter = vec2<f32>(hash2(c), hash2(c + vec2<f32>(17.0, 3.0))) - 0.5;
    let f = fract(u) - 0.5 - 0.7 * jitter;
    let r = length(f) / (0.7 + 0.6 * hash2(c + vec2<f32>(5.0, 11.0)));
    let hair = 1.0 - smoothstep(STUBBLE_R - fw, STUBBLE_R + fw, r);
    let mean = 3.1415927 * STUBBLE_R * STUBBLE_R;
    return mix(hair, mean, clamp(2.0 * fw - 0.5, 0.0, 1.0));
}

// The spacing of the lips' vertical lines, m (about 1 mm; our reading).
const LIP_LINE: f32 = 0.0011;

// The conjunctiva's colour where it shows in an eye's corner (our
// reading of photographs: the sclera's pinker, duller edge).
const CONJUNCTIVA: vec3<f32> = vec3<f32>(0.74, 0.52, 0.50);

// The face: skin with its painted borders and expression wrinkles.
@fragment
fn fs_face(v: PaintedOut, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    // The face is wound counter-clockwise seen from outside: a back face
    // near the lips (`paint.x`, their signed distance, above
    // MOUTH_INSIDE_LIMIT, prepended from face/appearance.rs) is the head's
    // inside seen through the parted lips, the mouth's dark inside (the
    // cavity behind the teeth stands for the rest). Elsewhere (a lid's
    // inside at an eye's corner) it is lit as skin.
    if (!front && v.paint.x > MOUTH_INSIDE_LIMIT) {
        return vec4<f32>(g.face_regions[3].rgb, 1.0);
    }
    let view_dir = normalize(g.camera.xyz - v.world);
    // Elsewhere a back face is a lid's inside, seen in an eye's corner
    // past the eyeball's curve: the conjunctiva, moist and pink, in the
    // socket's shade (lit softly, as the sclera beside it).
    if (!front) {
        let key = normalize(-g.key_dir.xyz);
        let lit = 0.35 + 0.4 * max(dot(-normalize(v.normal), key) + 0.6, 0.0) / 1.6;
        return vec4<f32>(CONJUNCTIVA * lit, 1.0);
    }
    var n = normalize(v.normal);
    if (dot(n, view_dir) < 0.0) {
        n = -n;
    }
    var base = inst.color.rgb * v.color.rgb;
    // The face frame's across and up axes in the world.
    let ax = (inst.model * vec4<f32>(1.0, 0.0, 0.0, 0.0)).xyz;
    let ay = (inst.model * vec4<f32>(0.0, 1.0, 0.0, 0.0)).xyz;
    let across = normalize(ax);
    // The stubble's cut hairs (`v.color.a`, the beard's density), sampled
    // in the plane the skin faces most, the face's front or the jaw's
    // side, so the dots do not stretch (where the plane changes, the
    // pattern's footprint is wide and the dots fade to their mean).
    let side = abs(dot(n, across)) > 0.6;
    let dots = stubble_dots(select(v.local.xy, v.local.zy, side));
    base = base * (1.0 - 0.6 * v.color.a * dots);
    // Painted borders (face/appearance.rs): each region covers
    // where its interpolated signed distance is positive, blended
    // over its soft border or one pixel, whichever is wider. The lips'
    // is computed here from the rest position, so their border is a
    // smooth curve (the Cupid's bow too) however coarse the mesh.
    let inside = vec3<f32>(lips_inside(v.rest, v.local.z) / LIP_SOFT, v.paint.w - abs(v.paint.y), v.paint.z);
    let aa = max(fwidth(inside), vec3<f32>(1.0));
    let cover = smoothstep(-aa, aa, inside);
    // The vermilion is not one pink: deeper and redder toward the mouth's
    // line, where the lip turns in and its skin is thinnest, paler by its
    // border (our reading of lip photographs), with the fine vertical
    // lines of the lips' skin (sulci, about 1 mm apart) and a wet shine.
    let lip_y = v.rest.y - g.lips[0].y;
    let lip_h = select(g.lips[0].w, g.lips[0].z, lip_y > 0.0);
    let to_border = clamp(abs(lip_y) / max(lip_h, 1e-4), 0.0, 1.0);
    let lip_colour = g.face_regions[0].rgb * mix(vec3<f32>(0.78, 0.70, 0.72), vec3<f32>(1.08, 1.10, 1.08), to_border);
    base = mix(base, lip_colour, cover.x);
    // A mouth stretched wide (a smile, fear's AU 20) pulls the skin beside
    // its corners into the opening, where it turns to face the mouth's
    // middle: there it is the corner's moist, shaded inner lip, not the
    // cheek's skin.
    let beside = length(vec2<f32>(max(abs(v.rest.x) - g.lips[0].x, 0.0), lip_y));
    let turned_in = -dot(n, across) * sign(v.rest.x);
    let commissure = smoothstep(0.012, 0.004, beside) * smoothstep(0.25, 0.55, turned_in);
    base = mix(base, g.face_regions[0].rgb * vec3<f32>(0.55, 0.40, 0.42), commissure);
    // The lines wander and vary in depth, strongest mid-lip.
    let sulci = v.rest.x / LIP_LINE
        + 0.7 * value_noise(v.rest.y / 0.0025 + select(0.0, 31.0, lip_y > 0.0))
        + 0.5 * value_noise(v.rest.x / 0.003);
    let sulci_fade = clamp(1.0 - 2.0 * fwidth(sulci), 0.0, 1.0);
    let depth = hash2(vec2<f32>(floor(sulci), select(1.0, 2.0, lip_y > 0.0)));
    let sulcus = 0.14 * depth * (1.0 - to_border * to_border) * sin(6.2831853 * sulci);
    n = normalize(n + across * (cover.x * sulci_fade * sulcus));
    // Brows as hairs: strokes along the hairs' lie, rising steeply out of
    // the brow's head and lying flatter toward the tail (our reading of how
    // brow hairs grow), denser in the body, over a faint base.
    let bx = abs(v.local.x);
    // (No branch: the strands' pixel footprint is a derivative, which
    // needs uniform control flow.)
    let rise = brow_rise(bx);
    let brow_across = (v.local.y - brow_lane(bx)) * cos(rise) / 0.0006;
    let brow_along = (bx * cos(rise) + v.local.y * sin(rise)) / 0.007;
    let hairs = strands(brow_across, brow_along, fwidth(brow_across), 0.8);
    // The head's hairs are sparse and soft: less contrast there.
    let head = clamp((bx - 0.012) / 0.012, 0.0, 1.0);
    let contrast = mix(0.2, 0.45, head);
    base = mix(base, g.face_regions[1].rgb, cover.y * (1.0 - contrast + contrast * hairs));
    base = mix(base, g.face_regions[2].rgb, cover.z);
    // Expression wrinkles (docs/model/face.md W1-W3, and W5 for the
    // profile): two families of lines, across the face's vertical axis
    // (phase y / L) and across its horizontal one (x / L), each a buckled
    // profile whose peak slope is W2's (`fold_tilt`), so the normal tilts
    // along the axis; their furrows are shadowed. Where a wavelength
    // covers under about three pixels the lines would alias: they fade
    // into their mean brightness instead, the furrows' mean shadow times
    // the mean cosine of the tilted normals (about 1 / sqrt(1 + s^2 / 2)),
    // so a wrinkled brow stays as dark far away as close up (the
    // filtering rule of Toksvig 2005, "Mipmapping normal maps").
    var furrow = 0.0;
    var tilt = 1.0;
    if (v.wrinkle.x + v.wrinkle.y > 1e-4) {
        let dx = normalize(ax - n * dot(ax, n));
        let dy = normalize(ay - n * dot(ay, n));
        let rx = clamp((0.33 - fwidth(v.wrinkle.z)) * 6.0, 0.0, 1.0);
        let ry = clamp((0.33 - fwidth(v.wrinkle.w)) * 6.0, 0.0, 1.0);
        // The lines wander a little (our choice: a fifth of their spacing
        // over 1.5 cm along them), as lines on a face do.
        let wx = v.wrinkle.z + 0.2 * (value_noise(v.local.y / 0.015) - 0.5);
        let wy = v.wrinkle.w + 0.2 * (value_noise(v.local.x / 0.015 + 11.0) - 0.5);
        let fx = fold_of(v.wrinkle.x);
        let fy = fold_of(v.wrinkle.y);
        n = normalize(n + dx * (v.wrinkle.x * fold_tilt(wx, fx, 1.0) * rx)
            + dy * (v.wrinkle.y * fold_tilt(wy, fy, 2.0) * ry));
        tilt = mix(inverseSqrt(1.0 + 0.5 * v.wrinkle.x * v.wrinkle.x), 1.0, rx)
            * mix(inverseSqrt(1.0 + 0.5 * v.wrinkle.y * v.wrinkle.y), 1.0, ry);
        // Where both families fold (the glabella under procerus and
        // corrugator) the deeper furrow's shadow holds: crossing folds
        // do not shade the skin twice.
        furrow = max(
            min(v.wrinkle.x, 1.0) * mix(fold_furrow_mean(fx), fold_furrow(wx, fx), rx),
            min(v.wrinkle.y, 1.0) * mix(fold_furrow_mean(fy), fold_furrow(wy, fy), ry),
        );
    }
    // Pores, finer on the forehead than over the nose and cheeks (our
    // choice of 0.5-0.8 mm spacing), on bare skin only.
    let bare = (1.0 - cover.x) * (1.0 - cover.z);
    let cell = select(0.0008, 0.0005, v.local.y > 0.02);
    n = select(n, pores(n, v.local.xy, ax, ay, cell), bare > 0.5);
    let top = SKIN_TOP * top_light(v.world, normalize(v.normal), 0.0);
    // The lips' wet film: a sharper, brighter highlight than skin's, most
    // on the fuller lower lip.
    let key = normalize(-g.key_dir.xyz);
    let c = max(dot(n, normalize(key + view_dir)), 0.0);
    let c16 = pow4(pow4(c));
    let wet = cover.x * select(0.10, 0.22, lip_y < 0.0) * c16 * c16;
    return vec4<f32>(skin(base, n, view_dir, (1.0 - furrow) * tilt, top) + vec3<f32>(wet), 1.0);
}


// The eye: a wet surface. Over the iris the normal is the cornea's, a
// sphere of 7.8 mm radius (Gullstrand's schematic eye) standing out of the
// 12 mm eyeball and meeting it at the limbus: its centre lies in front of
// the eye's centre of rotation, so the light's reflection slides over the
// iris as the eye turns, as a person's does. The highlight is a tear
// film's: small and bright.
const CORNEA_R: f32 = 0.65;
@fragment
fn fs_eye(v: VOut) -> @location(0) vec4<f32> {
    let d = normalize(v.local);
    var n_local = d;
    if (d.z > IRIS_COS) {
        let s2 = 1.0 - IRIS_COS * IRIS_COS;
        let c = IRIS_COS - sqrt(max(CORNEA_R * CORNEA_R - s2, 0.0));
        n_local = normalize(d - vec3<f32>(0.0, 0.0, c));
    }
    var n = normalize((inst.normal * vec4<f32>(n_local, 0.0)).xyz);
    let view_dir = normalize(g.camera.xyz - v.world);
    if (dot(n, view_dir) < 0.0) {
        n = -n;
    }
    // The upper lid's shadow: the lid's rim and lashes shade a band of
    // eyeball under its margin (about 2.5 mm, a fifth of the eyeball's
    // radius; our reading of portrait photographs), deepest at the margin.
    // The margin's height runs from its middle to the corners as a
    // parabola across the eye.
    let across = clamp(d.x / 0.8, -1.0, 1.0);
    let margin = mix(inst.color.x, inst.color.y, across * across);
    let under = clamp((margin - d.y) / 0.22, 0.0, 1.0);
    let lid_shade = 1.0 - 0.65 * (1.0 - under) * (1.0 - under);
    let base = eye_colour(v.local) * lid_shade;
    let key = normalize(-g.key_dir.xyz);
    let fill = normalize(-g.fill_dir.xyz);
    // Diffuse on the eyeball's own sphere, wrapped (the sclera is
    // translucent: light scattered in it brightens the eye's corners,
    // which face away from the lights), the highlights on the cornea.
    // The face's balance of lights (the skin's), so the whites are no
    // brighter than the skin round them would be in the same light.
    let ne = normalize(v.normal);
    let wrap = 0.6;
    let diffuse = (FACE_KEY * max(dot(ne, key) + wrap, 0.0) + FACE_FILL * max(dot(ne, fill) + wrap, 0.0))
        / (1.0 + wrap) + SKIN_TOP * top_light(v.world, ne, wrap);
    let c16 = pow4(pow4(max(dot(n, normalize(key + view_dir)), 0.0)));
    let c256 = pow4(pow4(c16));
    let cf64 = pow4(pow4(pow4(max(dot(n, normalize(fill + view_dir)), 0.0))));
    let spec = (1.6 * c256 + 0.12 * c16 + 0.5 * cf64 * cf64) * lid_shade;
    return vec4<f32>(base * (sky(ne) + diffuse) + vec3<f32>(spec), 1.0);
}
