//! Tables 12.1 and 12.2 as the seed prints them, against `codes::TABLE_T` / `TABLE_M`: the same
//! rows in the same order, the same codes, the same marks in columns [1] and [2].

use stanok_mazatrol::codes::{ttpc_table, Code, Mark, Series, TtpcRow};

const SEED: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../../shared/seeds/004_0c0655299d747f3b.txt"
);

/// One row of the seed: the code text and the two marks.
#[derive(Debug)]
struct SeedRow {
    codes: String,
    in_ttpc: Mark,
    select: Mark,
}

fn mark(text: &str) -> Mark {
    match text.trim() {
        "○" => Mark::Yes,
        "×" | "x" => Mark::No,
        "—" => Mark::NonModal,
        t if t.starts_with("Прим.") => Mark::Note(t["Прим.".len()..].trim().parse().unwrap()),
        t => panic!("unknown mark {t:?}"),
    }
}

/// The rows of the two tables (T first, then M).
fn seed_tables() -> (Vec<SeedRow>, Vec<SeedRow>) {
    let text = std::fs::read_to_string(SEED).expect("the seed is in ../shared/seeds");
    let mut t = Vec::new();
    let mut m = Vec::new();
    // 0: before the tables, 1: table 12.1, 2: table 12.2.
    let mut table = 0;
    for line in text.lines() {
        if line.starts_with("1. Функции для ЧПУ") {
            table = 1;
            continue;
        }
        if line.starts_with("2. Функции для ЧПУ") {
            table = 2;
            continue;
        }
        if table == 2 && line.starts_with("Примечание 1") {
            break;
        }
        let rows = match table {
            1 => &mut t,
            2 => &mut m,
            _ => continue,
        };
        let cols: Vec<&str> = line.split('\t').collect();
        if cols.len() != 4 || cols[0] == "Функция" {
            continue;
        }
        rows.push(SeedRow {
            codes: cols[1].to_string(),
            in_ttpc: mark(cols[2]),
            select: mark(cols[3]),
        });
    }
    (t, m)
}

/// G × 10 of `G43.4` text.
fn g10(text: &str) -> u32 {
    let t = text.trim().trim_start_matches('G');
    (t.parse::<f64>().unwrap() * 10.0).round() as u32
}

/// The seed's code column as (codes, is a range).
fn seed_codes(text: &str) -> (Vec<Code>, bool) {
    let t = text.replace(" to ", " ~ ").replace('–', " ~ ");
    if let Some((a, b)) = t.split_once('~') {
        let (a, b) = (g10(a), g10(b));
        let step = if a % 10 == 0 && b % 10 == 0 { 10 } else { 1 };
        return ((a..=b).step_by(step).map(Code::G).collect(), true);
    }
    let codes = t
        .split(['/', ','])
        .map(str::trim)
        .map(|c| match c.strip_prefix('M') {
            Some(m) => Code::M(m.parse().unwrap()),
            None => Code::G(g10(c)),
        })
        .collect();
    (codes, false)
}

fn compare(series: Series, seed: &[SeedRow], ours: &[TtpcRow]) {
    assert_eq!(seed.len(), ours.len(), "{}: row count", series.name());
    for (i, (s, o)) in seed.iter().zip(ours).enumerate() {
        let (codes, range) = seed_codes(&s.codes);
        if range {
            // A range lists the codes that exist within it.
            assert!(
                o.codes.iter().all(|c| codes.contains(c)),
                "{} row {i} ({}): {:?} not within {}",
                series.name(),
                o.function,
                o.codes,
                s.codes
            );
        } else {
            assert_eq!(codes, o.codes, "{} row {i} ({})", series.name(), o.function);
        }
        assert_eq!(
            (s.in_ttpc, s.select),
            (o.in_ttpc, o.select),
            "{} row {i} ({}, {})",
            series.name(),
            o.function,
            s.codes
        );
    }
}

#[test]
fn tables_12_1_and_12_2_match_the_seed_row_by_row() {
    let (t, m) = seed_tables();
    assert_eq!(t.len(), 56, "table 12.1 rows in the seed");
    assert_eq!(m.len(), 51, "table 12.2 rows in the seed");
    compare(Series::T, &t, ttpc_table(Series::T));
    compare(Series::M, &m, ttpc_table(Series::M));
}
