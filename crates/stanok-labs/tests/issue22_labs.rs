//! Issue 22 (conformance audit), lab-collection items 17 and 18: GOST-20999's number format and an
//! unset radius corrector.

mod labs_support;

use labs_support::*;
use stanok_syntax::Dialect;

fn gost(text: &str) -> Run {
    run_text(text, Dialect::Gost20999, |_| {})
}

#[test]
fn issue22_gost20999_numbers_have_4_digits_before_the_point_and_3_after() {
    // The audit's block: both words are out of format.
    let r = gost("N1 G1 X1.2345 Y10000. F100\nN2 M2\n");
    assert_eq!(r.error_codes(), ["lab::number-format"], "{:?}", r.errors);
    assert!(r.errors[0].message.starts_with("X:"), "{}", r.errors[0]);
    for bad in [
        "N1 G1 Y10000. F100",
        "N1 G1 Y-10000. F100",
        "N1 G1 X10000000 F100",
        "N1 G1 X0.0001 F100",
        "N1 G2 X10. Y0 I5.0005 J0 F100",
        "N1 G2 X10. Y0 R5.0005 F100",
    ] {
        let r = gost(&format!("{bad}\nN2 M2\n"));
        assert_eq!(
            r.error_codes(),
            ["lab::number-format"],
            "{bad}: {:?}",
            r.errors
        );
    }
    // The limits themselves, with and without a point (counts of 0.001 mm).
    // (N2 stays within the largest move of one block, 9999.999: see a_block_moves_at_most_9999_999.)
    let r = gost("N1 G1 X9999.999 Y-9999.999 F100\nN2 G1 X9999999 Y-0.001\nN3 M2\n");
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    xy(r.end_of(1), 9999.999, -9999.999, 1e-9, "N1");
    xy(r.end_of(2), 9999.999, -0.001, 1e-9, "N2");
}

#[test]
fn issue22_unset_radius_corrector_warns() {
    let text = "N1 G0 X0 Y0\nN2 G1 G41 D30 X10. Y0 F100\nN3 X20.\nN4 G40 X30.\nN5 M2\n";
    let r = gost(text);
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    let w: Vec<_> = r
        .warnings
        .iter()
        .filter(|w| w.code.to_string() == "lab::unset-corrector")
        .collect();
    assert_eq!(w.len(), 1, "{:?}", r.warnings);
    assert!(w[0].message.contains("D30"), "{}", w[0]);
    assert_eq!(w[0].span.line, 2);
    // Set: no warning.
    let r = run_text(text, Dialect::Gost20999, |o| {
        o.labs.correctors.insert(30, 5.0);
    });
    assert!(
        r.warnings
            .iter()
            .all(|w| w.code.to_string() != "lab::unset-corrector"),
        "{:?}",
        r.warnings
    );
}
