//! The G codes of the two series as data: which codes exist, their modal groups, which ones
//! Stanok simulates, and tables 12.1 / 12.2 of the seed (may a code be used during tool tip point
//! control, column [1]; may TTPC be selected while its mode is in force, column [2]).
//!
//! `docs/dialects/mazatrol-eia.md` §3.1 (groups), §16 (the TTPC tables), §17 (not simulated).
//! `tests/ttpc_tables.rs` reads the seed's tables and checks these rows against them, row by row.
//!
//! Codes are G numbers × 10 (`G43.4` → 434), as `stanok_syntax` words give them.

/// The control series (machine data `[mazatrol] series`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Series {
    /// Machining centres: M640M Pro, MATRIX (M series) — table 12.2.
    #[default]
    M,
    /// Mill-turn: M640MT 5X, M640MT Pro, MATRIX (T series) — table 12.1.
    T,
}

impl Series {
    /// "M-series" / "T-series".
    pub fn name(self) -> &'static str {
        match self {
            Series::M => "M-series",
            Series::T => "T-series",
        }
    }

    /// "12.2" / "12.1".
    pub fn table(self) -> &'static str {
        match self {
            Series::M => "12.2",
            Series::T => "12.1",
        }
    }
}

/// A modal group (Fanuc's numbers where Fanuc has one; `docs` §3.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[allow(missing_docs)]
pub enum Group {
    /// Group 00: one-shot codes.
    OneShot,
    Motion,
    Plane,
    Distance,
    StrokeCheck,
    Feed,
    Units,
    Compensation,
    Length,
    CycleReturn,
    SurfaceSpeed,
    Scaling,
    MacroModalCall,
    PathMode,
    WorkSystem,
    Rotation,
    PolarInput,
    RadiusInput,
    PolarInterpolation,
    Cylindrical,
    Mirror,
    Rotation3d,
    HighSpeed,
    Polygon,
    Hobbing,
    Longitudinal,
    CrossMachining,
}

impl Group {
    /// The group's description in diagnostics ("group 01 motion").
    pub fn describe(self) -> &'static str {
        match self {
            Group::OneShot => "group 00 one-shot",
            Group::Motion => "group 01 motion",
            Group::Plane => "group 02 plane",
            Group::Distance => "group 03 distance",
            Group::StrokeCheck => "group 04 stroke check",
            Group::Feed => "group 05 feed",
            Group::Units => "group 06 units",
            Group::Compensation => "group 07 radius compensation",
            Group::Length => "group 08 length offset",
            Group::CycleReturn => "group 10 cycle return",
            Group::SurfaceSpeed => "constant surface speed",
            Group::Scaling => "group 11 scaling",
            Group::MacroModalCall => "group 12 macro modal call",
            Group::PathMode => "group 13 path mode",
            Group::WorkSystem => "group 14 work system",
            Group::Rotation => "group 16 rotation",
            Group::PolarInput => "polar coordinate input",
            Group::RadiusInput => "X radius input",
            Group::PolarInterpolation => "polar coordinate interpolation",
            Group::Cylindrical => "cylindrical interpolation",
            Group::Mirror => "programmable mirror image",
            Group::Rotation3d => "3-D coordinate rotation",
            Group::HighSpeed => "high-speed machining",
            Group::Polygon => "polygon machining",
            Group::Hobbing => "hobbing",
            Group::Longitudinal => "longitudinal machining",
            Group::CrossMachining => "cross machining",
        }
    }
}

/// Which series a definition belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum On {
    /// Both.
    Both,
    /// M-series only.
    M,
    /// T-series only.
    T,
}

impl On {
    fn has(self, s: Series) -> bool {
        matches!(
            (self, s),
            (On::Both, _) | (On::M, Series::M) | (On::T, Series::T)
        )
    }
}

/// One G code of a series.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GDef {
    /// G × 10.
    pub code: u32,
    /// Its modal group.
    pub group: Group,
    /// What it does (for diagnostics).
    pub name: &'static str,
    /// The series that has it with this meaning.
    pub on: On,
    /// False for the functions of `docs` §17 that Stanok does not simulate.
    pub simulated: bool,
}

const fn g(code: u32, group: Group, name: &'static str, on: On) -> GDef {
    GDef {
        code,
        group,
        name,
        on,
        simulated: true,
    }
}

const fn ns(code: u32, group: Group, name: &'static str, on: On) -> GDef {
    GDef {
        code,
        group,
        name,
        on,
        simulated: false,
    }
}

use Group::*;

/// Every G code of both series (`docs` §3.1, §3.3, §17).
pub const G_CODES: &[GDef] = &[
    g(0, Motion, "positioning", On::Both),
    g(10, Motion, "linear interpolation", On::Both),
    ns(
        11,
        Motion,
        "external thread cutting with C-axis interpolation",
        On::T,
    ),
    g(20, Motion, "circular interpolation CW", On::Both),
    g(30, Motion, "circular interpolation CCW", On::Both),
    g(21, Motion, "spiral interpolation CW", On::Both),
    g(31, Motion, "spiral interpolation CCW", On::Both),
    g(40, OneShot, "dwell", On::Both),
    ns(50, HighSpeed, "high-speed machining mode", On::M),
    ns(61, Motion, "spline interpolation", On::M),
    ns(62, Motion, "NURBS interpolation", On::M),
    ns(70, Motion, "virtual axis interpolation", On::M),
    g(71, Cylindrical, "cylindrical interpolation", On::T),
    g(90, OneShot, "exact stop check", On::Both),
    g(100, OneShot, "data setting", On::Both),
    g(110, OneShot, "data setting cancel", On::Both),
    g(
        121,
        PolarInterpolation,
        "polar coordinate interpolation",
        On::T,
    ),
    g(
        131,
        PolarInterpolation,
        "polar coordinate interpolation off",
        On::T,
    ),
    g(160, Plane, "Z-C plane selection", On::T),
    g(170, Plane, "XY plane selection", On::Both),
    g(180, Plane, "ZX plane selection", On::Both),
    g(190, Plane, "YZ plane selection", On::Both),
    g(200, Units, "inch input", On::Both),
    g(210, Units, "metric input", On::Both),
    g(220, StrokeCheck, "stored stroke check on", On::Both),
    g(230, StrokeCheck, "stored stroke check off", On::Both),
    g(270, OneShot, "reference point return check", On::Both),
    g(280, OneShot, "reference point return", On::Both),
    g(290, OneShot, "return from reference point", On::Both),
    g(300, OneShot, "2nd/3rd/4th reference point return", On::Both),
    g(301, OneShot, "floating reference point return", On::Both),
    g(310, OneShot, "skip function", On::Both),
    g(311, OneShot, "multi-step skip 1", On::M),
    g(312, OneShot, "multi-step skip 2", On::M),
    g(313, OneShot, "multi-step skip 3", On::M),
    g(320, Motion, "thread cutting", On::T),
    g(330, Motion, "thread cutting", On::Both),
    g(340, Motion, "variable-lead thread cutting", On::T),
    ns(360, OneShot, "automatic tool offset (X)", On::T),
    ns(370, OneShot, "automatic tool length measurement", On::Both),
    ns(365, OneShot, "measurement preparation", On::T),
    ns(375, OneShot, "measurement calculation", On::T),
    ns(380, OneShot, "compensation vector hold", On::M),
    ns(390, OneShot, "corner circular interpolation", On::M),
    g(400, Compensation, "radius compensation cancel", On::Both),
    g(410, Compensation, "radius compensation left", On::Both),
    g(420, Compensation, "radius compensation right", On::Both),
    g(
        460,
        Compensation,
        "nose radius compensation, automatic direction",
        On::T,
    ),
    g(430, Length, "tool length offset +", On::Both),
    g(440, Length, "tool length offset -", On::Both),
    g(434, Length, "tool tip point control type 1", On::Both),
    g(435, Length, "tool tip point control type 2", On::Both),
    g(490, Length, "tool length offset cancel", On::Both),
    g(450, OneShot, "tool position offset, increase", On::M),
    g(460, OneShot, "tool position offset, decrease", On::M),
    g(470, OneShot, "tool position offset, double increase", On::M),
    g(480, OneShot, "tool position offset, double decrease", On::M),
    g(500, Scaling, "scaling off", On::M),
    g(510, Scaling, "scaling on", On::M),
    g(
        500,
        OneShot,
        "coordinate system setting / spindle speed clamp",
        On::T,
    ),
    g(501, Mirror, "programmable mirror image off", On::M),
    g(511, Mirror, "programmable mirror image on", On::M),
    ns(502, Polygon, "polygon machining off", On::T),
    ns(512, Polygon, "polygon machining on", On::T),
    g(520, OneShot, "local coordinate system", On::Both),
    g(530, OneShot, "machine coordinate positioning", On::Both),
    g(525, OneShot, "MAZATROL coordinate system off", On::T),
    g(535, OneShot, "MAZATROL coordinate system on", On::T),
    g(540, WorkSystem, "work coordinate system 1", On::Both),
    g(550, WorkSystem, "work coordinate system 2", On::Both),
    g(560, WorkSystem, "work coordinate system 3", On::Both),
    g(570, WorkSystem, "work coordinate system 4", On::Both),
    g(580, WorkSystem, "work coordinate system 5", On::Both),
    g(590, WorkSystem, "work coordinate system 6", On::Both),
    g(541, WorkSystem, "additional work coordinate systems", On::M),
    g(600, OneShot, "unidirectional positioning", On::M),
    g(610, PathMode, "exact stop mode", On::Both),
    g(611, PathMode, "geometry compensation", On::Both),
    g(620, PathMode, "automatic corner override", On::Both),
    g(630, PathMode, "tapping mode", On::M),
    g(640, PathMode, "cutting mode", On::Both),
    g(650, OneShot, "macro simple call", On::Both),
    g(660, MacroModalCall, "macro modal call", On::Both),
    g(661, MacroModalCall, "macro modal call B", On::M),
    g(670, MacroModalCall, "macro modal call cancel", On::Both),
    g(680, Rotation, "coordinate rotation", On::M),
    g(690, Rotation, "coordinate rotation cancel", On::M),
    g(680, Rotation, "facing-turret mirror image on", On::T),
    g(690, Rotation, "facing-turret mirror image off", On::T),
    g(685, Rotation3d, "programmed coordinate rotation", On::Both),
    g(
        695,
        Rotation3d,
        "programmed coordinate rotation cancel",
        On::Both,
    ),
    g(700, OneShot, "finishing cycle", On::T),
    g(710, OneShot, "stock removal in turning", On::T),
    g(720, OneShot, "stock removal in facing", On::T),
    g(730, OneShot, "pattern repeating cycle", On::T),
    g(740, OneShot, "face grooving / peck drilling cycle", On::T),
    g(750, OneShot, "OD grooving cycle", On::T),
    g(760, OneShot, "multiple threading cycle", On::T),
    g(770, Motion, "turning cycle", On::T),
    g(780, Motion, "threading cycle", On::T),
    g(790, Motion, "facing cycle", On::T),
    g(800, Motion, "canned cycle cancel", On::Both),
    g(730, Motion, "high-speed peck drilling cycle", On::M),
    g(740, Motion, "left-hand tapping cycle", On::M),
    g(760, Motion, "fine boring cycle", On::M),
    g(810, Motion, "drilling cycle", On::M),
    g(820, Motion, "spot drilling cycle", On::M),
    g(830, Motion, "peck drilling cycle", On::M),
    g(840, Motion, "tapping cycle", On::M),
    g(850, Motion, "boring cycle", On::M),
    g(860, Motion, "boring cycle, spindle stop", On::M),
    g(870, Motion, "back boring cycle", On::M),
    g(880, Motion, "boring cycle, manual retract", On::M),
    g(890, Motion, "boring cycle, dwell", On::M),
    g(830, Motion, "face drilling cycle", On::T),
    g(840, Motion, "face tapping cycle", On::T),
    g(850, Motion, "face boring cycle", On::T),
    g(870, Motion, "side drilling cycle", On::T),
    g(880, Motion, "side tapping cycle", On::T),
    g(890, Motion, "side boring cycle", On::T),
    g(900, Distance, "absolute", On::Both),
    g(910, Distance, "incremental", On::Both),
    g(920, OneShot, "coordinate system setting", On::Both),
    g(925, OneShot, "workpiece coordinate system rotation", On::M),
    g(930, Feed, "inverse time feed", On::M),
    g(940, Feed, "feed per minute", On::Both),
    g(950, Feed, "feed per revolution", On::Both),
    g(960, SurfaceSpeed, "constant surface speed", On::T),
    g(970, SurfaceSpeed, "constant surface speed cancel", On::T),
    g(980, CycleReturn, "return to the initial level", On::Both),
    g(990, CycleReturn, "return to the R level", On::Both),
    g(1090, OneShot, "two process sequences in one program", On::T),
    g(
        1100,
        CrossMachining,
        "cross-machining axis selection",
        On::T,
    ),
    g(
        1110,
        CrossMachining,
        "cross-machining axis selection cancel",
        On::T,
    ),
    g(
        1120,
        OneShot,
        "M/S/T/B output to the opposite system",
        On::T,
    ),
    g(1130, Hobbing, "hobbing mode cancel", On::T),
    ns(1143, Hobbing, "hobbing mode", On::T),
    ns(1200, Longitudinal, "longitudinal machining on", On::T),
    ns(1210, Longitudinal, "longitudinal machining off", On::T),
    g(1220, PolarInput, "polar coordinate input on", On::T),
    g(1230, PolarInput, "polar coordinate input off", On::T),
    g(1221, RadiusInput, "X-axis radius input on", On::T),
    g(1231, RadiusInput, "X-axis radius input off", On::T),
];

/// The definition of G `code` on `series`, if the series has it.
pub fn g_def(series: Series, code: u32) -> Option<&'static GDef> {
    G_CODES.iter().find(|d| d.code == code && d.on.has(series))
}

/// `G43.4`, `G02`, `G54.1` as text from a code × 10.
pub fn g_name(code: u32) -> String {
    match code % 10 {
        0 => format!("G{:02}", code / 10),
        tenth => format!("G{:02}.{tenth}", code / 10),
    }
}

/// A mark of tables 12.1 / 12.2.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mark {
    /// ○.
    Yes,
    /// ×.
    No,
    /// — (a non-modal code).
    NonModal,
    /// "Прим. n" (note n of table 12.2).
    Note(u8),
}

/// A code of a table row.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Code {
    /// G × 10.
    G(u32),
    /// M code.
    M(u32),
}

/// One row of table 12.1 / 12.2.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TtpcRow {
    /// The function, as the table names it (English, TTPC spec §12).
    pub function: &'static str,
    /// The codes of the row.
    pub codes: &'static [Code],
    /// Column [1]: allowed while TTPC is on.
    pub in_ttpc: Mark,
    /// Column [2]: TTPC selectable while the code's mode is in force.
    pub select: Mark,
}

const fn row(
    function: &'static str,
    codes: &'static [Code],
    in_ttpc: Mark,
    select: Mark,
) -> TtpcRow {
    TtpcRow {
        function,
        codes,
        in_ttpc,
        select,
    }
}

use Code::G as Gc;
use Mark::{No as N, NonModal as Nm, Note, Yes as Y};

/// Table 12.1, in the seed's order.
pub const TABLE_T: &[TtpcRow] = &[
    row("positioning", &[Gc(0)], Y, Y),
    row("linear interpolation", &[Gc(10)], Y, Y),
    row(
        "external thread cutting with C-axis interpolation",
        &[Gc(11)],
        N,
        N,
    ),
    row("circular interpolation", &[Gc(20), Gc(30)], N, N),
    row("helical interpolation", &[Gc(20), Gc(30)], N, N),
    row("spiral interpolation", &[Gc(21), Gc(31)], N, N),
    row("dwell", &[Gc(40)], Y, Nm),
    row("cylindrical interpolation", &[Gc(71)], N, N),
    row("exact stop check", &[Gc(90)], Y, Nm),
    row("data setting", &[Gc(100)], N, Nm),
    row("data setting cancel", &[Gc(110)], N, Nm),
    row("polar coordinate interpolation", &[Gc(121)], N, N),
    row("polar coordinate interpolation off", &[Gc(131)], N, N),
    row(
        "plane selection",
        &[Gc(160), Gc(170), Gc(180), Gc(190)],
        N,
        Nm,
    ),
    row("inch/metric input", &[Gc(200), Gc(210)], N, Y),
    row("stored stroke check on/off", &[Gc(220), Gc(230)], Y, Y),
    row("reference point return check", &[Gc(270)], N, Nm),
    row("reference point return", &[Gc(280)], N, Nm),
    row("return from reference point", &[Gc(290)], N, Nm),
    row("2nd/3rd/4th reference point return", &[Gc(300)], N, Nm),
    row("floating reference point return", &[Gc(301)], N, Nm),
    row("skip function", &[Gc(310)], N, Nm),
    row("thread cutting", &[Gc(320), Gc(330)], N, N),
    row("variable-lead thread cutting", &[Gc(340)], N, N),
    row("automatic tool offset", &[Gc(360), Gc(370)], N, Nm),
    row(
        "measurement preparation/calculation",
        &[Gc(365), Gc(375)],
        N,
        Nm,
    ),
    row(
        "tool nose radius compensation",
        &[Gc(400), Gc(410), Gc(420), Gc(460)],
        N,
        N,
    ),
    row(
        "coordinate system setting / maximum spindle speed",
        &[Gc(500), Gc(920)],
        N,
        Nm,
    ),
    row("polygon machining off/on", &[Gc(502), Gc(512)], N, N),
    row("local coordinate system", &[Gc(520)], N, Nm),
    row("machine coordinate system selection", &[Gc(530)], N, Nm),
    row(
        "MAZATROL coordinate system off/on",
        &[Gc(525), Gc(535)],
        N,
        Nm,
    ),
    row(
        "workpiece coordinate systems 1 to 6",
        &[Gc(540), Gc(550), Gc(560), Gc(570), Gc(580), Gc(590)],
        N,
        N,
    ),
    row("exact stop mode", &[Gc(610)], Y, Y),
    row("geometry compensation", &[Gc(611)], N, N),
    row("automatic corner override", &[Gc(620)], N, N),
    row("cutting mode", &[Gc(640)], Y, Y),
    row("macro simple call", &[Gc(650)], N, N),
    row("macro modal call", &[Gc(660)], N, N),
    row("macro modal call off", &[Gc(670)], N, N),
    row("subprogram call", &[Code::M(98), Code::M(99)], Y, Nm),
    row(
        "facing-turret mirror image on/off",
        &[Gc(680), Gc(690)],
        N,
        N,
    ),
    row(
        "programmed coordinate rotation on/off",
        &[Gc(685), Gc(695)],
        N,
        N,
    ),
    row("canned cycles", CYCLES_T, N, N),
    row("absolute/incremental", &[Gc(900), Gc(910)], Y, Y),
    row("feed per minute", &[Gc(940)], Y, Y),
    row("feed per revolution", &[Gc(950)], N, N),
    row("constant surface speed on/off", &[Gc(960), Gc(970)], N, N),
    row("two process sequences in one program", &[Gc(1090)], Y, Nm),
    row(
        "cross-machining axis selection on/off",
        &[Gc(1100), Gc(1110)],
        N,
        N,
    ),
    row("M/S/T/B output to the opposite system", &[Gc(1120)], Y, Nm),
    row("hobbing mode cancel", &[Gc(1130)], Y, N),
    row("hobbing mode", &[Gc(1143)], N, N),
    row("longitudinal machining on/off", &[Gc(1200), Gc(1210)], N, N),
    row("polar coordinate input on/off", &[Gc(1220), Gc(1230)], N, N),
    row("X-axis radius input on/off", &[Gc(1221), Gc(1231)], N, Y),
];

/// Table 12.2, in the seed's order.
pub const TABLE_M: &[TtpcRow] = &[
    row("positioning", &[Gc(0)], Y, Y),
    row("linear interpolation", &[Gc(10)], Y, Y),
    row("circular interpolation", &[Gc(20), Gc(30)], Note(3), N),
    row("helical interpolation", &[Gc(20), Gc(30)], N, N),
    row("spiral interpolation", &[Gc(21), Gc(31)], N, N),
    row("dwell", &[Gc(40)], Y, Nm),
    row("high-speed machining mode", &[Gc(50)], N, N),
    row("spline interpolation", &[Gc(61)], N, N),
    row("NURBS interpolation", &[Gc(62)], N, N),
    row("virtual axis interpolation", &[Gc(70)], N, N),
    row("exact stop check", &[Gc(90)], Y, Nm),
    row("programmed parameter input", &[Gc(100)], N, Nm),
    row("plane selection", &[Gc(170), Gc(180), Gc(190)], Y, Nm),
    row("inch/metric input", &[Gc(200), Gc(210)], N, Y),
    row("pre-move stroke check on/off", &[Gc(220), Gc(230)], Y, Y),
    row("reference point return check", &[Gc(270)], N, Nm),
    row("reference point return", &[Gc(280)], N, Nm),
    row("return from reference point", &[Gc(290)], N, Nm),
    row("2nd/3rd/4th reference point return", &[Gc(300)], N, Nm),
    row("skip function", &[Gc(310)], N, Nm),
    row(
        "multi-step skip 1 to 3",
        &[Gc(311), Gc(312), Gc(313)],
        N,
        Nm,
    ),
    row("thread cutting", &[Gc(330)], N, N),
    row("automatic tool length measurement", &[Gc(370)], N, Nm),
    row(
        "tool radius compensation",
        &[Gc(380), Gc(390), Gc(400), Gc(410), Gc(420)],
        N,
        Nm,
    ),
    row(
        "tool length offset",
        &[Gc(430), Gc(440), Gc(490)],
        Note(1),
        Note(2),
    ),
    row(
        "tool position offset",
        &[Gc(450), Gc(460), Gc(470), Gc(480)],
        N,
        N,
    ),
    row("scaling on/off", &[Gc(500), Gc(510)], N, N),
    row(
        "programmable mirror image off/on",
        &[Gc(501), Gc(511)],
        N,
        N,
    ),
    row("local coordinate system", &[Gc(520)], N, Nm),
    row("machine coordinate system selection", &[Gc(530)], N, Nm),
    row(
        "workpiece coordinate system selection",
        &[Gc(540), Gc(550), Gc(560), Gc(570), Gc(580), Gc(590)],
        N,
        Y,
    ),
    row("additional workpiece coordinate systems", &[Gc(541)], N, Y),
    row("unidirectional positioning", &[Gc(600)], N, Nm),
    row("exact stop mode", &[Gc(610)], Y, Y),
    row("geometry compensation", &[Gc(611)], N, N),
    row("automatic corner override", &[Gc(620)], N, N),
    row("tapping mode", &[Gc(630)], N, N),
    row("cutting mode", &[Gc(640)], Y, Y),
    row("macro simple call", &[Gc(650)], N, N),
    row("macro modal call A", &[Gc(660)], N, N),
    row("macro modal call B", &[Gc(661)], N, N),
    row("macro modal call off", &[Gc(670)], N, N),
    row("subprogram call", &[Code::M(98), Code::M(99)], Y, Nm),
    row("coordinate rotation on/off", &[Gc(680), Gc(690)], N, N),
    row("canned cycles", CYCLES_M, N, N),
    row("absolute/incremental", &[Gc(900), Gc(910)], Y, Y),
    row("coordinate system setting", &[Gc(920)], N, Nm),
    row("workpiece coordinate system rotation", &[Gc(925)], N, Nm),
    row("inverse time feed", &[Gc(930)], Y, Y),
    row("feed per minute", &[Gc(940)], Y, Y),
    row("feed per revolution", &[Gc(950)], N, N),
];

/// G70 … G89 of the T-series that exist.
const CYCLES_T: &[Code] = &[
    Gc(700),
    Gc(710),
    Gc(720),
    Gc(730),
    Gc(740),
    Gc(750),
    Gc(760),
    Gc(770),
    Gc(780),
    Gc(790),
    Gc(800),
    Gc(830),
    Gc(840),
    Gc(850),
    Gc(870),
    Gc(880),
    Gc(890),
];

/// G70 … G89 of the M-series that exist.
const CYCLES_M: &[Code] = &[
    Gc(730),
    Gc(740),
    Gc(760),
    Gc(800),
    Gc(810),
    Gc(820),
    Gc(830),
    Gc(840),
    Gc(850),
    Gc(860),
    Gc(870),
    Gc(880),
    Gc(890),
];

/// The series' table.
pub fn ttpc_table(series: Series) -> &'static [TtpcRow] {
    match series {
        Series::M => TABLE_M,
        Series::T => TABLE_T,
    }
}

/// The row of `code` (the helical row for an arc with a third axis word).
pub fn ttpc_row(series: Series, code: Code, helical: bool) -> Option<&'static TtpcRow> {
    let table = ttpc_table(series);
    let mut rows = table.iter().filter(|r| r.codes.contains(&code));
    let first = rows.next()?;
    if helical {
        return rows.next().or(Some(first));
    }
    Some(first)
}

/// The ON codes of the combined rows, to which column [2]'s "no" applies (AMB-26, `docs` §16).
/// The T-series G54–G59 "no" is not applied (`docs` D24).
pub fn select_blocked_by(series: Series, code: u32) -> bool {
    const ON_CODES: &[u32] = &[
        20, 30, 21, 31, 320, 330, 340, 71, 121, 410, 420, 460, 512, 611, 620, 630, 660, 661, 680,
        685, 730, 740, 760, 770, 780, 790, 810, 820, 830, 840, 850, 860, 870, 880, 890, 950, 960,
        1100, 1143, 1200, 1220, 510, 511, 11, 61, 62, 70, 50,
    ];
    if !ON_CODES.contains(&code) {
        return false;
    }
    ttpc_row(series, Code::G(code), false).is_some_and(|r| r.select == Mark::No)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_table_code_is_a_code_of_its_series() {
        for series in [Series::M, Series::T] {
            for r in ttpc_table(series) {
                for c in r.codes {
                    if let Code::G(g) = c {
                        assert!(
                            g_def(series, *g).is_some(),
                            "{} {} {}",
                            series.name(),
                            r.function,
                            g_name(*g)
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn series_meanings_differ_where_the_docs_say() {
        assert_eq!(g_def(Series::M, 460).unwrap().group, Group::OneShot);
        assert_eq!(g_def(Series::T, 460).unwrap().group, Group::Compensation);
        assert_eq!(g_def(Series::M, 500).unwrap().group, Group::Scaling);
        assert_eq!(g_def(Series::T, 500).unwrap().group, Group::OneShot);
        assert!(g_def(Series::M, 960).is_none());
        assert!(g_def(Series::T, 930).is_none());
        assert!(!g_def(Series::M, 62).unwrap().simulated);
        assert_eq!(g_name(434), "G43.4");
        assert_eq!(g_name(20), "G02");
        assert_eq!(g_name(1221), "G122.1");
    }

    #[test]
    fn helical_arcs_have_their_own_row() {
        let r = ttpc_row(Series::M, Code::G(20), false).unwrap();
        assert_eq!(r.in_ttpc, Mark::Note(3));
        let h = ttpc_row(Series::M, Code::G(20), true).unwrap();
        assert_eq!(h.function, "helical interpolation");
        assert_eq!(h.in_ttpc, Mark::No);
    }

    #[test]
    fn column_two_blocks_on_codes_only() {
        // M-series radius compensation is "—" in column [2] (its column [1] "no" refuses it).
        assert!(!select_blocked_by(Series::M, 410));
        assert!(select_blocked_by(Series::T, 410));
        assert!(!select_blocked_by(Series::T, 400));
        assert!(select_blocked_by(Series::T, 960));
        assert!(!select_blocked_by(Series::T, 970));
        assert!(!select_blocked_by(Series::T, 540));
        assert!(!select_blocked_by(Series::M, 540));
        assert!(select_blocked_by(Series::M, 810));
        assert!(!select_blocked_by(Series::M, 800));
    }
}
