//! The quantities the canonical commands are made of: poses, planes, units, feed modes and feed
//! laws, the constant-surface-speed law, spindle directions. Frames and units as in `canon.rs`.

use serde::Serialize;

/// Constant surface speed (G96) as the machine executes it, continuously: at every instant the
/// spindle turns at
///
/// ```text
///   n = clamp( v / (2π·r), min_rpm, max_rpm )      r = |p[axis] − centre|   (machine coordinates)
///   r → 0 (below 1 µm): n = max_rpm (no maximum: min_rpm, else 0)
/// ```
///
/// so the cutting speed at the tool stays `v` while the tool moves across the part. The
/// interpreter fills it from its own words (AxiOMA S/LMAXS/LMINS/REFAX, LinuxCNC S/D) and from
/// the offsets in force (the work zero of `axis` is the spindle centre line); the planner and the
/// simulated machine evaluate it at every point of the path.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SurfaceSpeedLaw {
    /// Cutting speed v, mm/min.
    pub mm_per_min: f64,
    /// `Pose::to_array` index of the transverse axis whose distance from the centre is the radius.
    pub axis: u8,
    /// Machine coordinate of the spindle centre line on that axis, mm.
    pub centre: f64,
    /// Lower limit, rev/min (0 = none).
    pub min_rpm: f64,
    /// Upper limit, rev/min (0 = none).
    pub max_rpm: f64,
}

impl SurfaceSpeedLaw {
    /// Radii below this are the centre line, mm.
    pub const CENTRE_RADIUS: f64 = 1e-3;

    /// Spindle speed, rev/min, with the tool at `position` (all nine axes, machine coordinates).
    pub fn rpm_at(&self, position: &[f64; 9]) -> f64 {
        let r = (position[(self.axis as usize).min(8)] - self.centre).abs();
        let hi = if self.max_rpm > 0.0 {
            self.max_rpm
        } else {
            f64::INFINITY
        };
        let lo = self.min_rpm.max(0.0).min(hi);
        let raw = if r < Self::CENTRE_RADIUS || !r.is_finite() {
            if hi.is_finite() {
                hi
            } else {
                lo
            }
        } else {
            self.mm_per_min / (std::f64::consts::TAU * r)
        };
        if raw.is_finite() {
            raw.clamp(lo, hi)
        } else {
            lo
        }
    }
}

/// A point of all nine axes LinuxCNC knows: X Y Z (mm), A B C (deg), U V W (mm).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Pose {
    /// X, mm.
    pub x: f64,
    /// Y, mm.
    pub y: f64,
    /// Z, mm.
    pub z: f64,
    /// A, degrees.
    pub a: f64,
    /// B, degrees.
    pub b: f64,
    /// C, degrees.
    pub c: f64,
    /// U, mm.
    pub u: f64,
    /// V, mm.
    pub v: f64,
    /// W, mm.
    pub w: f64,
}

impl Pose {
    /// All axes zero.
    pub const ZERO: Pose = Pose {
        x: 0.0,
        y: 0.0,
        z: 0.0,
        a: 0.0,
        b: 0.0,
        c: 0.0,
        u: 0.0,
        v: 0.0,
        w: 0.0,
    };

    /// The nine values in the order X Y Z A B C U V W.
    pub fn to_array(&self) -> [f64; 9] {
        [
            self.x, self.y, self.z, self.a, self.b, self.c, self.u, self.v, self.w,
        ]
    }

    /// Builds a pose from X Y Z A B C U V W.
    pub fn from_array(v: [f64; 9]) -> Self {
        Pose {
            x: v[0],
            y: v[1],
            z: v[2],
            a: v[3],
            b: v[4],
            c: v[5],
            u: v[6],
            v: v[7],
            w: v[8],
        }
    }

    /// The Cartesian tool point (X, Y, Z).
    pub fn xyz(&self) -> [f64; 3] {
        [self.x, self.y, self.z]
    }

    /// A copy with X, Y, Z replaced.
    pub fn with_xyz(mut self, p: [f64; 3]) -> Self {
        self.x = p[0];
        self.y = p[1];
        self.z = p[2];
        self
    }
}

/// Index of each axis in [`Pose::to_array`] order.
pub const AXIS_LETTERS: [char; 9] = ['X', 'Y', 'Z', 'A', 'B', 'C', 'U', 'V', 'W'];

/// A programming plane. The pair order is LinuxCNC's (first, second) and fixes the sense of
/// "counter-clockwise": right-handed about the plane normal.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Plane {
    /// G17: (X, Y), normal +Z.
    XY,
    /// G18: (Z, X), normal +Y.
    ZX,
    /// G19: (Y, Z), normal +X.
    YZ,
}

impl Plane {
    /// Indices into X,Y,Z of (first, second, normal) axes.
    pub fn axes(self) -> (usize, usize, usize) {
        match self {
            Plane::XY => (0, 1, 2),
            Plane::ZX => (2, 0, 1),
            Plane::YZ => (1, 2, 0),
        }
    }
}

/// Length units a program is written in (internal values are always mm).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum LengthUnits {
    /// G21 / G71.
    Millimetres,
    /// G20 / G70.
    Inches,
}

impl LengthUnits {
    /// Millimetres per program unit.
    pub fn mm_per_unit(self) -> f64 {
        match self {
            LengthUnits::Millimetres => 1.0,
            LengthUnits::Inches => 25.4,
        }
    }
}

/// How F is to be read by the motion stage.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum FeedMode {
    /// G94: mm/min along the path.
    UnitsPerMinute,
    /// G93: each feed move takes 1/F minutes.
    InverseTime,
    /// G95: mm per spindle revolution.
    UnitsPerRevolution,
}

/// How a feed move's speed follows the machine: with it the motion stage times the move from the
/// command alone. `feed` beside it stays the move's nominal path feed, mm/min at the commanded
/// values, which printers, reports and converters read.
///
/// The interpreter states its feed modes in the stream (`SetFeedMode`, `SetFeedRate`,
/// `SetSpindleSpeed`, `SetSurfaceSpeedLaw`, `StartSpindleSync`/`StopSpindleSync`) and completes every
/// motion with the law they put in force at its place in the stream; rapids carry the law in force
/// too (their speed does not depend on it).
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub enum FeedLaw {
    /// G94: `feed` mm/min along the feed length.
    #[default]
    PerMinute,
    /// G93: the move takes 1/F minutes; `feed` is the mm/min that does that over its length.
    InverseTime,
    /// G95: `mm_per_rev` per revolution of the main spindle at its commanded `rpm`
    /// (`feed` = the product).
    PerRevolution {
        /// Feed per revolution, mm.
        mm_per_rev: f64,
        /// The main spindle's commanded speed, rev/min.
        rpm: f64,
    },
    /// G95 under G96: per revolution of the main spindle, whose speed follows `law` along the path.
    SurfaceSpeed {
        /// Feed per revolution, mm.
        mm_per_rev: f64,
        /// The main spindle's constant-surface-speed law (boxed: it is rare and 40 bytes, and
        /// every motion of every program carries a `FeedLaw` — docs/decisions.md, issue 26).
        law: Box<SurfaceSpeedLaw>,
    },
    /// Spindle-synchronised (G33, G33.1, G76, AxiOMA G276): `pitch` per revolution of the main
    /// spindle at `rpm`; the feed override does not apply.
    SpindleSync {
        /// Advance per revolution, mm.
        pitch: f64,
        /// The main spindle's commanded speed, rev/min.
        rpm: f64,
    },
}

impl FeedLaw {
    /// The per-minute law (serialised moves leave it out).
    pub fn is_per_minute(&self) -> bool {
        matches!(self, FeedLaw::PerMinute)
    }
}

/// Spindle rotation sense, as seen looking from the spindle towards the work.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum SpindleDirection {
    /// M3.
    Clockwise,
    /// M4.
    CounterClockwise,
}

/// When an auxiliary function acts relative to the motion of its block (AxiOMA prefix/postfix).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum AuxTiming {
    /// Before the block's motion.
    Prefix,
    /// After the block's motion.
    Postfix,
}
