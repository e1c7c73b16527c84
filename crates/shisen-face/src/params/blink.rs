//! The blink constants (`blink` in the muscle database).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Blink constants (face.md 6 and table D note).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BlinkParams {
    /// AU45 upper palpebral contraction at full closure, more than 0 and
    /// at most 10 (2.9, the thesis's value, table D note; an expression's
    /// contractions are at most 1, and 10 is over three times the
    /// thesis's).
    #[schemars(range(max = 10.0), extend("exclusiveMinimum" = 0.0))]
    pub contraction: f64,
    /// Closing time, s, 0.01-1 (0.080; a spontaneous blink's lid closes
    /// in about a tenth of a second: Evinger, Manning & Sibony 1991,
    /// Invest. Ophthalmol. Vis. Sci. 32:387). The bounds are a frame and
    /// a slow, drowsy blink (our choice).
    #[schemars(range(min = 0.01, max = 1.0))]
    pub close_s: f64,
    /// Opening time, s, 0.01-2 (0.120; the lid reopens more slowly than
    /// it closes: Evinger et al. 1991). The bounds are a frame and a
    /// slow, drowsy reopening (our choice).
    #[schemars(range(min = 0.01, max = 2.0))]
    pub open_s: f64,
    /// Inverse Gaussian mean mu of the spontaneous blink interval, s,
    /// 0.5-60 (4.0). People at rest blink 17 times a minute (3.5 s), in
    /// conversation 26 (2.3 s), reading 4.5 (13 s): Bentivoglio et al.
    /// 1997, Mov. Disord. 12:1028. Half a second (120 a minute) is beyond
    /// any reported mean rate; a minute, a subject who hardly blinks.
    #[schemars(range(min = 0.5, max = 60.0))]
    pub mean_interval_s: f64,
    /// Inverse Gaussian shape lambda, s, 0.5-1000 (13.94). The intervals'
    /// coefficient of variation is sqrt(mu / lambda): 0.54 by default;
    /// the bounds allow a CV from 0.02 to 11 at the default mean.
    #[schemars(range(min = 0.5, max = 1000.0))]
    pub shape_s: f64,
    /// Spontaneous blinks only while the face is neutral (the thesis's
    /// rule). Off by default: people blink whatever they feel.
    #[serde(default)]
    pub neutral_only: bool,
    /// Gaze shifts smaller than this never trigger a blink, degrees,
    /// 0-180 (20: Evinger et al. 1994, Exp. Brain Res. 100:337; 180 is
    /// the largest turn of the gaze there is).
    #[schemars(range(min = 0.0, max = 180.0))]
    pub gaze_trigger_min_deg: f64,
    /// Gaze shifts at least this large always trigger a blink, degrees,
    /// more than 0 and at most 180 (60), and more than
    /// `gaze_trigger_min_deg`.
    #[schemars(range(max = 180.0), extend("exclusiveMinimum" = 0.0))]
    pub gaze_trigger_max_deg: f64,
    /// Upper-lid vertical travel per unit of eyeball vertical travel
    /// (lid follows the eye's pitch), 0-2 (0.8; the upper lid follows the
    /// eye about one to one in vertical saccades: Becker & Fuchs 1988,
    /// J. Neurophysiol. 60:1227).
    #[schemars(range(min = 0.0, max = 2.0))]
    pub lid_follow_gain: f64,
    /// Lower-lid vertical travel per unit of eyeball vertical travel,
    /// 0-2 (0.3 if absent: the lower lid follows the pitch less than the
    /// upper).
    #[serde(default = "default_lower_lid_follow_gain")]
    #[schemars(range(min = 0.0, max = 2.0))]
    pub lower_lid_follow_gain: f64,
    /// How far the lower lid's middle rises per unit contraction of the
    /// orbital orbicularis (AU 6), m: the cheek the muscle raises pushes
    /// the lower lid up and narrows the eye from below, the mark of a
    /// felt smile (Ekman, Friesen & Hager 2002, FACS Manual, AU 6;
    /// Duchenne's smile). Default 0.008: happiness's orbital contraction
    /// (0.25) lifts it 2 mm more than the sphincter's own field does, the
    /// opening closing by about two fifths (our choice); 0 leaves the lid
    /// to the sphincter's field (the seed profile).
    /// 0-0.02: at most 2 cm per unit contraction (the eye's whole opening
    /// is about 1 cm).
    #[serde(default = "default_cheek_lid_rise")]
    #[schemars(range(min = 0.0, max = 0.02))]
    pub cheek_lid_rise_m: f64,
    /// Gain of the upper lid's raise on a relaxation of the upper
    /// palpebral orbicularis (an expression's negative contraction, AU 5;
    /// face.md L1). The thesis codes AU 5 as that muscle relaxing, so the
    /// lid can only travel back along the muscle's own closing path, and
    /// fear's -0.18 lifts it half a millimetre, under the iris's top edge;
    /// the lid is in fact raised by levator palpebrae, which lifts it
    /// 12-17 mm from down- to upgaze (Beard 1981, Ptosis, 3rd ed.). The
    /// raise the relaxation gives on its own is multiplied by this gain
    /// (then bounded by `levator_max_raise_m`). Default 6 (our choice: fear
    /// shows white above the iris, as face.md section 4 asks); 1 is the
    /// thesis's lid. More than 0 and at most 30 (five times the default).
    #[serde(default = "default_levator_gain")]
    #[schemars(range(max = 30.0), extend("exclusiveMinimum" = 0.0))]
    pub levator_gain: f64,
    /// Highest the upper lid's mid margin rises above its rest, metres
    /// (L1: the raise saturates smoothly towards it), or `None` for the
    /// thesis's unbounded, linear lid. A lid at rest covers the iris's top
    /// 1-2 mm, its margin 4-5 mm above the corneal reflex (MRD1; the
    /// clinical norm in AAO's Basic and Clinical Science Course, section 7,
    /// Orbit, Eyelids and Lacrimal System); the default
    /// `Some(0.0045)` lets the widest eyes show about 3 mm of white above
    /// the iris (our choice), and keeps a relaxation near -1 (a value the
    /// thesis's subjects chose, appendix A) from folding the lid. More
    /// than 0 and at most 0.02 (the levator's whole excursion, 12-17 mm).
    #[serde(default = "default_levator_max_raise")]
    #[schemars(range(max = 0.02), extend("exclusiveMinimum" = 0.0))]
    pub levator_max_raise_m: Option<f64>,
    /// Blink intervals are stretched by this factor while the VH is
    /// engaged (guarding or attacking): the spontaneous blink rate drops
    /// under visual demand (17 /min at rest against 4.5 /min while
    /// reading, a factor of 3.8: Bentivoglio et al. 1997, Mov. Disord.
    /// 12:1028). Default 3 (gaze-evoked blinks come on top, so the rate
    /// while sparring stays near 10 /min); 1 turns the effect off.
    /// 0.25-10: from four times more blinks (conversation raises the rate
    /// by half, 26 /min: Bentivoglio et al. 1997) to ten times fewer
    /// (more than twice the reading factor).
    #[serde(default = "default_engaged_scale")]
    #[schemars(range(min = 0.25, max = 10.0))]
    pub engaged_interval_scale: f64,
    /// Blink rate rises with arousal: the rate is multiplied by
    /// `1 + arousal_gain x arousal x intensity` (arousal of the emotion,
    /// 0-1, [`crate::tables::Emotion::arousal`]). Spontaneous blink
    /// rate goes up with arousal, anxiety and stress (Stern, Walrath &
    /// Goldstein 1984, Psychophysiology 21:22, a review). Default 0.5
    /// (our choice within that trend); 0 turns it off. 0-3: at most four
    /// times the rate at full arousal (six times the default's rise).
    #[serde(default = "default_arousal_gain")]
    #[schemars(range(min = 0.0, max = 3.0))]
    pub arousal_gain: f64,
}

fn default_arousal_gain() -> f64 {
    0.5
}

fn default_engaged_scale() -> f64 {
    3.0
}

fn default_levator_gain() -> f64 {
    6.0
}

fn default_levator_max_raise() -> Option<f64> {
    Some(0.0045)
}

fn default_cheek_lid_rise() -> f64 {
    0.008
}

fn default_lower_lid_follow_gain() -> f64 {
    0.3
}
