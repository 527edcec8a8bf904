//! A 5-axis swarf cut on `5axis-bc-head` (AxiOMA TRAORI): the tool leans 20° in XZ (B20) and
//! cuts along Y with its flank, starting and ending outside the stock. The removed cross-section
//! is the tilted flute rectangle below the top, `2R·depth / cos β` (the flute end is above the
//! stock), times the stock's width in Y: the tool axis from the kinematics at every setpoint.

mod common;
use common::*;

const TOOLS: &str = r#"
[[tool]]
number = 2
flute_length = 30.0
reach = 40.0
[[tool.edge]]
length = [100.0]
radius = 5.0
"#;

fn program(b: f64) -> String {
    format!(
        "G17 G90 G15 G191 G71 G72 G172 G272 G94 G97 G49 G40 G00 G80 G98\n\
         G53 G153 G193 G64 BRISK CUT2DF ORIAXES\n\
         N10 T2 M6\n\
         N20 G43\n\
         N25 S8000 M3\n\
         N27 G00 Z150\n\
         N30 TRAORI\n\
         N40 G00 X50 Y-20 Z20 B{b}\n\
         N50 G01 Z-10 F1000\n\
         N60 G01 Y80\n\
         N70 G00 Z50\n\
         N80 TRAFOOF\n\
         N90 M30\n"
    )
}

fn removed(tag: &str, b: f64) -> serde_json::Value {
    let prog = temp_in(tag, "swarf.nc", &program(b));
    let tools = temp_in(tag, "tools.toml", TOOLS);
    let (code, out, err) = stanok(&[
        "run",
        &prog,
        "--json",
        "--machine",
        "5axis-bc-head",
        "--tools",
        &tools,
        "--stock",
        "box:X0,Y0,Z-30:X100,Y60,Z0",
        "--stock-frame",
        "machine",
    ]);
    assert_eq!(code, 0, "{err}\n{out}");
    json(&out)["stock"].clone()
}

#[test]
fn a_swarf_cut_with_the_tool_leaning_20_degrees() {
    let stock = removed("swarf20", 20.0);
    let got = stock["removed_volume_mm3"]["total"].as_f64().unwrap();
    let want = 2.0 * 5.0 * 10.0 / 20f64.to_radians().cos() * 60.0;
    assert!((got - want).abs() / want < 0.005, "{got} vs {want}");
    assert_eq!(stock["collisions"], serde_json::json!([]), "{stock}");
    // The same cut upright removes 10 × 10 × 60: the tilt is the kinematics'.
    let upright = removed("swarf0", 0.0);
    let got0 = upright["removed_volume_mm3"]["total"].as_f64().unwrap();
    assert!((got0 - 6000.0).abs() / 6000.0 < 0.005, "{got0}");
}
