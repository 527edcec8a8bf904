//! Small rules of the language, each a pure function (`docs/dialects/mazatrol-eia.md`): decimal
//! point types (§2.3), the T word of the T-series (§8.2), G76's packed P word (§11.6), the files a
//! subprogram may be in (§14), G34's pieces (§5.12) and the system variables (§15.6).

use std::path::{Path, PathBuf};

/// How a letter's number without a decimal point is read under decimal point type 1.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dimension {
    /// A length: × 0.001 mm (× 0.0001 in).
    Length,
    /// An angle: × 0.001°.
    Angle,
    /// A dwell time of G04 X/U: × 0.001 s.
    Time,
    /// As written (F S T M H D L P N G O K E).
    Plain,
}

/// The dimension of `letter` in a block (`dwell`: the block has G04; `q_length`: Q is a length in
/// the block's cycle).
pub fn dimension(letter: u8, dwell: bool, q_length: bool) -> Dimension {
    match letter {
        b'X' | b'U' if dwell => Dimension::Time,
        b'X' | b'Y' | b'Z' | b'U' | b'V' | b'W' | b'I' | b'J' | b'K' | b'R' => Dimension::Length,
        b'Q' if q_length => Dimension::Length,
        b'A' | b'B' | b'C' => Dimension::Angle,
        _ => Dimension::Plain,
    }
}

/// The value of a number word: `text` is the word's number as written (after the letter).
/// Type 1 scales a number without a point by the least input increment; type 2 never scales.
pub fn scaled(value: f64, text: &str, dim: Dimension, decimal_type: u8, inch: bool) -> f64 {
    if decimal_type != 1 || text.contains('.') {
        return value;
    }
    match dim {
        Dimension::Length if inch => value * 1e-4,
        Dimension::Length | Dimension::Angle | Dimension::Time => value * 1e-3,
        Dimension::Plain => value,
    }
}

/// `T tt oo` of the T-series: (tool, offset). A T of at most two digits is an offset only
/// (`T01` = tool 0, offset 1) [F].
pub fn t_word(value: u32) -> (u32, u32) {
    (value / 100, value % 100)
}

/// G76's first-block P word `m r a` (two digits each): (finishing passes, chamfer tenths,
/// tool angle).
pub fn g76_p(value: u32) -> (u32, u32, u32) {
    (value / 10_000, (value / 100) % 100, value % 100)
}

/// The files, in order, where program O `number` may be on one directory of the subroutine path
/// [D]: `O1234`, `O1234.nc`, `O1234.eia`, `O1234.min`, `1234.nc` (four digits at least, case of the
/// letter as found on disk).
pub fn subprogram_files(dir: &Path, number: u32) -> Vec<PathBuf> {
    let n = format!("{number:04}");
    let mut out = Vec::new();
    for stem in [format!("O{n}"), format!("o{n}")] {
        for ext in ["", ".nc", ".NC", ".eia", ".EIA", ".min", ".MIN"] {
            out.push(dir.join(format!("{stem}{ext}")));
        }
    }
    out.push(dir.join(format!("{n}.nc")));
    out
}

/// G34's pieces: the move of `length` (along its longer axis) with lead `f + k·n` growing by `k`
/// per revolution, cut at the end of each revolution. Returns (end distance, lead of the piece)
/// per piece: piece n (from revolution n to n + 1) is run at `f + k·(n + ½)`, its end at
/// `ℓ(n + 1) = (n + 1)·f + k·(n + 1)²/2` [D]. `None` when the lead would reach zero before the
/// end or when more than `max` revolutions are needed.
pub fn g34_pieces(length: f64, f: f64, k: f64, max: usize) -> Option<Vec<(f64, f64)>> {
    if !(length > 0.0 && f > 0.0 && length.is_finite() && f.is_finite() && k.is_finite()) {
        return None;
    }
    let mut out = Vec::new();
    let mut n = 0.0_f64;
    loop {
        let lead = f + k * (n + 0.5);
        let end = (n + 1.0) * f + k * (n + 1.0) * (n + 1.0) / 2.0;
        if f + k * n <= 0.0 || lead <= 0.0 {
            return None;
        }
        if end >= length - 1e-9 {
            out.push((length, lead));
            return Some(out);
        }
        out.push((end, lead));
        n += 1.0;
        if out.len() > max {
            return None;
        }
    }
}

/// A system variable (`docs` §15.6).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SysVar {
    /// M-series tool n: length wear (#2001…).
    LengthWear(u32),
    /// M-series tool n: length geometry (#2201…).
    LengthGeometry(u32),
    /// M-series tool n: radius wear (#2401…).
    RadiusWear(u32),
    /// M-series tool n: radius geometry (#2601…).
    RadiusGeometry(u32),
    /// T-series offset n: wear of axis 0 = X, 1 = Z, 2 = R, 3 = tip (#2001, #2101, #2201, #2301).
    TurnWear(u32, u8),
    /// T-series offset n: geometry of axis 0 = X, 1 = Z, 2 = R (#2701, #2801, #2901).
    TurnGeometry(u32, u8),
    /// #3000 macro alarm.
    Alarm,
    /// #3003 single-block control.
    SingleBlock,
    /// #3004 feed hold / override control.
    FeedControl,
    /// #3006 stop with a message.
    Message,
    /// #3001, #3002, #3011, #3012 (not simulated).
    Clock,
    /// #4001–#4022: modal G code of group n of the block before.
    ModalG(u32),
    /// #4102… : the address value of the block before (B D F H M N O S T).
    Address(u8),
    /// #5001–#5006: block end point, work coordinates, axis i.
    BlockEnd(usize),
    /// #5021–#5026: machine coordinates.
    Machine(usize),
    /// #5041–#5046: current position, work coordinates.
    Current(usize),
    /// #5061–#5066: skip position.
    Skip(usize),
    /// #5081–#5083: tool length offset in force (X Y Z).
    ToolOffset(usize),
    /// #5201–#5206: external offset, #5221… G54 … #5321… G59 (system 0 = external, 1…6), axis.
    WorkOffset(u8, usize),
    /// #7001…: G54.1 P n, axis.
    ExtraOffset(u32, usize),
}

/// The system variable of number `n` on `t_series`, if it is one.
pub fn sys_var(n: u32, t_series: bool) -> Option<SysVar> {
    use SysVar::*;
    let axis = |base: u32| (n - base) as usize;
    Some(match n {
        2001..=2064 if t_series => TurnWear(n - 2000, 0),
        2101..=2164 if t_series => TurnWear(n - 2100, 1),
        2201..=2264 if t_series => TurnWear(n - 2200, 2),
        2301..=2364 if t_series => TurnWear(n - 2300, 3),
        2701..=2764 if t_series => TurnGeometry(n - 2700, 0),
        2801..=2864 if t_series => TurnGeometry(n - 2800, 1),
        2901..=2964 if t_series => TurnGeometry(n - 2900, 2),
        2001..=2200 if !t_series => LengthWear(n - 2000),
        2201..=2400 if !t_series => LengthGeometry(n - 2200),
        2401..=2600 if !t_series => RadiusWear(n - 2400),
        2601..=2800 if !t_series => RadiusGeometry(n - 2600),
        3000 => Alarm,
        3003 => SingleBlock,
        3004 => FeedControl,
        3006 => Message,
        3001 | 3002 | 3011 | 3012 => Clock,
        4001..=4022 => ModalG(n - 4000),
        4102 => Address(b'B'),
        4107 => Address(b'D'),
        4109 => Address(b'F'),
        4111 => Address(b'H'),
        4113 => Address(b'M'),
        4114 => Address(b'N'),
        4115 => Address(b'O'),
        4119 => Address(b'S'),
        4120 => Address(b'T'),
        5001..=5006 => BlockEnd(axis(5001)),
        5021..=5026 => Machine(axis(5021)),
        5041..=5046 => Current(axis(5041)),
        5061..=5066 => Skip(axis(5061)),
        5081..=5083 => ToolOffset(axis(5081)),
        5201..=5206 => WorkOffset(0, axis(5201)),
        5221..=5346 if (n - 5221) % 20 < 6 => {
            WorkOffset(((n - 5221) / 20 + 1) as u8, ((n - 5221) % 20) as usize)
        }
        7001..=7946 if (n - 7001) % 20 < 6 => {
            ExtraOffset((n - 7001) / 20 + 1, ((n - 7001) % 20) as usize)
        }
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimal_point_types() {
        let x = dimension(b'X', false, false);
        assert_eq!(scaled(10.0, "10", x, 1, false), 0.01);
        assert_eq!(scaled(10.0, "10.", x, 1, false), 10.0);
        assert_eq!(scaled(10.0, "10", x, 2, false), 10.0);
        assert!((scaled(10.0, "10", x, 1, true) - 0.001).abs() < 1e-15);
        assert_eq!(
            scaled(1500.0, "1500", dimension(b'X', true, false), 1, false),
            1.5
        );
        assert_eq!(
            scaled(90.0, "90", dimension(b'B', false, false), 1, false),
            0.09
        );
        assert_eq!(
            scaled(100.0, "100", dimension(b'F', false, false), 1, false),
            100.0
        );
        assert_eq!(dimension(b'Q', false, false), Dimension::Plain);
        assert_eq!(dimension(b'Q', false, true), Dimension::Length);
    }

    #[test]
    fn t_and_g76_words() {
        assert_eq!(t_word(101), (1, 1));
        assert_eq!(t_word(1202), (12, 2));
        assert_eq!(t_word(1), (0, 1));
        assert_eq!(t_word(200), (2, 0));
        assert_eq!(g76_p(20060), (2, 0, 60));
        assert_eq!(g76_p(11055), (1, 10, 55));
    }

    #[test]
    fn subprogram_file_names() {
        let f = subprogram_files(Path::new("/lib"), 12);
        assert_eq!(f[0], Path::new("/lib/O0012"));
        assert_eq!(f[1], Path::new("/lib/O0012.nc"));
        assert!(f.contains(&PathBuf::from("/lib/0012.nc")));
        assert_eq!(
            subprogram_files(Path::new("d"), 123456)[0],
            Path::new("d/O123456")
        );
    }

    #[test]
    fn g34_pieces_follow_the_lead_law() {
        // F 2, K 0.5 per revolution over 10 mm: ℓ(1) = 2.25, ℓ(2) = 5, ℓ(3) = 8.25, then 10.
        let p = g34_pieces(10.0, 2.0, 0.5, 100).unwrap();
        assert_eq!(
            p,
            vec![(2.25, 2.25), (5.0, 2.75), (8.25, 3.25), (10.0, 3.75)]
        );
        // A shrinking lead that reaches zero: refused.
        assert!(g34_pieces(10.0, 2.0, -1.0, 100).is_none());
        assert!(g34_pieces(0.0, 2.0, 0.0, 100).is_none());
        assert_eq!(
            g34_pieces(3.0, 2.0, 0.0, 100).unwrap(),
            vec![(2.0, 2.0), (3.0, 2.0)]
        );
    }

    #[test]
    fn system_variables() {
        assert_eq!(sys_var(2001, false), Some(SysVar::LengthWear(1)));
        assert_eq!(sys_var(2201, false), Some(SysVar::LengthGeometry(1)));
        assert_eq!(sys_var(2800, false), Some(SysVar::RadiusGeometry(200)));
        assert_eq!(sys_var(2101, true), Some(SysVar::TurnWear(1, 1)));
        assert_eq!(sys_var(2964, true), Some(SysVar::TurnGeometry(64, 2)));
        assert_eq!(sys_var(2065, true), None);
        assert_eq!(sys_var(5221, false), Some(SysVar::WorkOffset(1, 0)));
        assert_eq!(sys_var(5243, false), Some(SysVar::WorkOffset(2, 2)));
        assert_eq!(sys_var(5326, false), Some(SysVar::WorkOffset(6, 5)));
        assert_eq!(sys_var(5327, false), None);
        assert_eq!(sys_var(7001, false), Some(SysVar::ExtraOffset(1, 0)));
        assert_eq!(sys_var(7943, false), Some(SysVar::ExtraOffset(48, 2)));
        assert_eq!(sys_var(5003, false), Some(SysVar::BlockEnd(2)));
        assert_eq!(sys_var(4001, false), Some(SysVar::ModalG(1)));
        assert_eq!(sys_var(4109, false), Some(SysVar::Address(b'F')));
        assert_eq!(sys_var(3000, false), Some(SysVar::Alarm));
        assert_eq!(sys_var(1000, false), None);
    }
}
