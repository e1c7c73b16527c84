//! Human measurements the body, the gaze laws and the face share, in one
//! place: the eye geometry and ranges of the seed's table 1 (gaze.md 2)
//! and the neck's range of motion (gaze.md 9, after Takagi & Takeda).
//! Metres, kilograms, degrees.

/// The trunk.
pub mod trunk {
    /// The waist joint (the trunk's pivot, about L5/S1) at rest, world
    /// `[x, y, z]`, m.
    pub const WAIST: [f64; 3] = [0.0, 1.0, 0.0];
}

/// The arms (the body plan's, shared with the punch planner).
pub mod arm {
    /// Upper arm length (shoulder to elbow), m.
    pub const UPPER: f64 = 0.28;
    /// Forearm length (elbow to glove centre), m.
    pub const FOREARM: f64 = 0.30;
    /// Shoulder pivot at rest, world m: left (`side = 0`, +X) or right.
    pub fn shoulder(side: usize) -> [f64; 3] {
        let x = if side == 0 { 0.19 } else { -0.19 };
        [x, 1.45, 0.0]
    }
}

/// The eyes (gaze.md 2, table 1).
pub mod eye {
    /// Eyeball radius (22 mm diameter), m.
    pub const RADIUS: f64 = 0.011;
    /// Angular radius of the iris, to the outer edge of its limbal ring,
    /// seen from the eyeball's centre, deg: a 12 mm iris (horizontal
    /// visible iris diameter 11.7 mm, Rüfer et al. 2005, Cornea 24:259) on
    /// an 11 mm eyeball reaches sin 32 deg x 11 = 5.8 mm from the axis.
    pub const IRIS_DEG: f64 = 32.0;
    /// Angular radius where the iris's stroma ends and its dark limbal
    /// ring begins, deg.
    pub const LIMBUS_DEG: f64 = 30.0;
    /// Angular radius of the drawn pupil, deg: a 3-4 mm daylight pupil
    /// (about 9 deg) enlarged to 5.7 mm so it stays visible at sparring distance.
    pub const PUPIL_DEG: f64 = 15.0;
    /// Interpupillary distance, m.
    pub const IPD: f64 = 0.0619;
    /// Eye centre below the top of the head, m.
    pub const BELOW_TOP: f64 = 0.1255;
    /// Eyeball mass, kg.
    pub const MASS: f64 = 0.0075;
    /// Eyeball moment of inertia about a diameter, kg m^2: a uniform solid
    /// sphere, 2/5 m r^2 (what the physics gives the eye's ball collider).
    pub const INERTIA: f64 = 0.4 * MASS * RADIUS * RADIUS;
    /// Horizontal range of motion, +- deg.
    pub const YAW_RANGE_DEG: f64 = 55.0;
    /// Vertical range of motion, +- deg.
    pub const PITCH_RANGE_DEG: f64 = 45.0;
}

/// The neck's range of motion (gaze.md 9).
pub mod neck {
    /// Rotation left/right, +- deg.
    pub const YAW_DEG: f64 = 70.0;
    /// Extension (looking up), deg.
    pub const PITCH_UP_DEG: f64 = 50.0;
    /// Flexion (looking down), deg, as a positive angle.
    pub const PITCH_DOWN_DEG: f64 = 60.0;
    /// Lateral bend, +- deg.
    pub const ROLL_DEG: f64 = 50.0;
}
