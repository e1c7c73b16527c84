//! Takagi & Takeda's published numbers, kept as printed (degrees,
//! seconds): table 1 (head fits to measured movements) and the parameters
//! of their subjective test 2 (gaze.md 10).

use super::law::{AxisTrack, GazeShift, Sigmoid};

/// Head axis of a table row.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    /// Horizontal (azimuth).
    Yaw,
    /// Vertical.
    Pitch,
}

/// A row of Takagi & Takeda's table 1 (head fits to measured data), as printed:
/// degrees and seconds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeadFitRow {
    /// Gaze target (horizontal, vertical) in degrees.
    pub target_deg: (f64, f64),
    /// Axis.
    pub axis: Axis,
    /// `a` (deg).
    pub a_deg: f64,
    /// `b`.
    pub b: f64,
    /// `c` (1/s).
    pub c: f64,
    /// Offset (deg).
    pub offset_deg: f64,
    /// `T1` (s).
    pub t1: f64,
    /// `T2` (s).
    pub t2: f64,
    /// `T3` (s).
    pub t3: f64,
}

impl HeadFitRow {
    /// The row's sigmoid (radians).
    pub fn sigmoid(&self) -> Sigmoid {
        Sigmoid::from_deg(self.a_deg, self.b, self.c, self.t1, self.t2, self.t3)
    }

    /// The row as an axis track, with its offset.
    pub fn track(&self) -> AxisTrack {
        AxisTrack {
            offset: self.offset_deg.to_radians(),
            ..AxisTrack::sigmoid(self.sigmoid())
        }
    }
}

const fn fit(
    target_deg: (f64, f64),
    axis: Axis,
    a_deg: f64,
    b: f64,
    c: f64,
    offset_deg: f64,
    t: [f64; 3],
) -> HeadFitRow {
    HeadFitRow {
        target_deg,
        axis,
        a_deg,
        b,
        c,
        offset_deg,
        t1: t[0],
        t2: t[1],
        t3: t[2],
    }
}

/// Table 1 of Takagi & Takeda (gaze.md section 10): head parameters fitted to
/// measured movements toward targets at horizontal -30 deg.
pub const TABLE1_HEAD_FITS: [HeadFitRow; 8] = [
    fit(
        (-30.0, -60.0),
        Axis::Pitch,
        -17.3,
        0.5,
        4.0,
        2.6,
        [0.3, 2.1, 0.4],
    ),
    fit(
        (-30.0, -60.0),
        Axis::Yaw,
        -16.2,
        1.1,
        5.0,
        0.0,
        [0.7, 1.3, 0.8],
    ),
    fit(
        (-30.0, -30.0),
        Axis::Pitch,
        -3.3,
        1.0,
        4.0,
        0.3,
        [1.0, 1.1, 0.7],
    ),
    fit(
        (-30.0, -30.0),
        Axis::Yaw,
        -18.6,
        1.0,
        3.0,
        0.4,
        [0.6, 1.7, 0.5],
    ),
    fit(
        (-30.0, 30.0),
        Axis::Pitch,
        11.6,
        4.0,
        4.0,
        0.6,
        [0.6, 1.5, 0.4],
    ),
    fit(
        (-30.0, 30.0),
        Axis::Yaw,
        -17.4,
        1.2,
        4.0,
        0.4,
        [0.7, 1.4, 0.4],
    ),
    fit(
        (-30.0, 60.0),
        Axis::Pitch,
        31.0,
        1.1,
        2.0,
        2.0,
        [0.6, 1.7, 0.3],
    ),
    fit(
        (-30.0, 60.0),
        Axis::Yaw,
        -17.3,
        0.7,
        4.0,
        0.0,
        [0.4, 1.7, 0.5],
    ),
];

/// A row of the subjective test 2 table (gaze.md section 10): `[a_deg, T1, T2, T3]`
/// for head (H) and gaze (S) on each axis; all with `b = 1`, `c = 8`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Test2Row {
    /// Target (horizontal, vertical), degrees.
    pub target_deg: (f64, f64),
    /// Head yaw `[a_deg, T1, T2, T3]`.
    pub head_yaw: [f64; 4],
    /// Head pitch.
    pub head_pitch: [f64; 4],
    /// Gaze yaw.
    pub gaze_yaw: [f64; 4],
    /// Gaze pitch.
    pub gaze_pitch: [f64; 4],
}

/// `b` of every subjective-test-2 row.
pub const TEST2_B: f64 = 1.0;
/// `c` of every subjective-test-2 row (1/s).
pub const TEST2_C: f64 = 8.0;

/// Head (H) and gaze (S) parameters of Takagi & Takeda's subjective test 2.
pub const TABLE_TEST2: [Test2Row; 4] = [
    Test2Row {
        target_deg: (-35.0, -35.0),
        head_yaw: [-18.6, 0.2, 1.6, 0.0],
        head_pitch: [-33.0, 0.2, 1.6, 0.0],
        gaze_yaw: [-35.0, 0.1, 1.5, 0.2],
        gaze_pitch: [-35.0, 0.1, 1.5, 0.2],
    },
    Test2Row {
        target_deg: (-40.0, 30.0),
        head_yaw: [-24.0, 0.15, 1.65, 0.0],
        head_pitch: [16.6, 0.15, 1.65, 0.0],
        gaze_yaw: [-40.0, 0.0, 1.6, 0.2],
        gaze_pitch: [30.0, 0.0, 1.6, 0.2],
    },
    Test2Row {
        target_deg: (40.0, 50.0),
        head_yaw: [32.3, 0.4, 1.4, 0.0],
        head_pitch: [39.5, 0.4, 1.4, 0.0],
        gaze_yaw: [40.0, 0.0, 1.7, 0.1],
        gaze_pitch: [50.0, 0.0, 1.7, 0.1],
    },
    Test2Row {
        target_deg: (55.0, -25.0),
        head_yaw: [27.0, 0.15, 1.55, 0.1],
        head_pitch: [-13.3, 0.15, 1.55, 0.1],
        gaze_yaw: [55.0, 0.0, 1.6, 0.2],
        gaze_pitch: [-25.0, 0.0, 1.6, 0.2],
    },
];

impl Test2Row {
    fn axis(p: [f64; 4]) -> Sigmoid {
        Sigmoid::from_deg(p[0], TEST2_B, TEST2_C, p[1], p[2], p[3])
    }

    /// The four sigmoids of the row (head yaw, head pitch, gaze yaw, gaze pitch).
    pub fn sigmoids(&self) -> [Sigmoid; 4] {
        [
            self.head_yaw,
            self.head_pitch,
            self.gaze_yaw,
            self.gaze_pitch,
        ]
        .map(Self::axis)
    }

    /// The row as a gaze shift.
    pub fn gaze_shift(&self) -> GazeShift {
        let [hy, hp, gy, gp] = self.sigmoids();
        GazeShift {
            head_yaw: AxisTrack::sigmoid(hy),
            head_pitch: AxisTrack::sigmoid(hp),
            gaze_yaw: AxisTrack::sigmoid(gy),
            gaze_pitch: AxisTrack::sigmoid(gp),
        }
    }
}
