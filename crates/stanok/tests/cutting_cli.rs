//! `stanok cutting turn` through the real command line: the spec's example C (grey iron,
//! 68.10 m/min, n = 180.6 → 160 rpm) as JSON, and the exit codes of the cases the document's
//! data cannot answer.

mod common;
use common::*;

#[test]
fn cutting_turn_json_reproduces_example_c() {
    let (code, out, err) = stanok(&[
        "cutting",
        "turn",
        "--material",
        "grey-iron",
        "--hb",
        "210",
        "--surface",
        "casting",
        "--tool-material",
        "VK6",
        "--diameter",
        "120",
        "--depth",
        "2",
        "--life",
        "60",
        "--machine-speeds",
        "100,125,160,200,250",
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let v = json(&out);
    let p = &v["passes"][0];
    let num = |k: &str| p[k].as_f64().unwrap_or(f64::NAN);
    assert!((num("v_m_min") - 68.10).abs() <= 0.01, "{p}");
    assert!((num("n_rpm") - 180.6).abs() <= 0.05, "{p}");
    assert_eq!(num("n_act_rpm"), 160.0);
    assert!((num("v_act_m_min") - 60.32).abs() <= 0.01);
    assert!((num("k_mv") - 0.8815).abs() <= 0.00005);
    assert_eq!(num("cv"), 243.0);
    // Every step carries its cells; table 2.4's range is there.
    let steps = p["steps"].as_array().unwrap();
    assert!(steps.iter().any(|s| s["cells"]
        .as_array()
        .unwrap()
        .iter()
        .any(|c| c["table"] == "2.4" && c["value"] == 1.5)));
    assert_eq!(v["not_in_document"].as_array().unwrap().len(), 3);
}

#[test]
fn cutting_turn_says_what_the_document_cannot_compute() {
    let (code, _, err) = stanok(&[
        "cutting",
        "turn",
        "--material",
        "malleable-iron",
        "--hb",
        "163",
        "--tool-material",
        "VK6",
        "--diameter",
        "43",
        "--depth",
        "2",
    ]);
    assert_eq!(code, 1);
    assert!(err.contains("no Cv row for malleable cast iron"), "{err}");
    // A steel without its strength is an argument error (2), not a guess.
    let (code, _, err) = stanok(&[
        "cutting",
        "turn",
        "--material",
        "carbon-steel",
        "--tool-material",
        "T15K6",
        "--diameter",
        "50",
        "--depth",
        "2",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("--sigma-b"), "{err}");
}
