//! `--var FILE`: a LinuxCNC parameter file kept between runs, as LinuxCNC keeps its PARAMETER_FILE
//! (read at start, written at exit): offsets, G28/G30 positions, G92 and the active system carry
//! over from one run to the next.

use std::path::PathBuf;
mod common;
use common::stanok;

fn dir() -> PathBuf {
    let d = std::env::temp_dir().join(format!("stanok-var-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn value(var: &str, n: u32) -> Option<f64> {
    var.lines().find_map(|l| {
        let mut w = l.split_whitespace();
        (w.next()? == n.to_string()).then(|| w.next()?.parse().ok())?
    })
}

#[test]
fn offsets_and_g92_carry_over_between_runs() {
    let d = dir();
    let var = d.join("sim.var");
    let _ = std::fs::remove_file(&var);
    let var_s = var.display().to_string();
    // Run 1: set G55's origin, store a G28 position, apply G92, end in G55 (M2 returns to G54:
    // write the program with % so the run ends in G55, like a LinuxCNC session stopped there).
    let first = d.join("first.ngc");
    std::fs::write(
        &first,
        "%\nG21\nG10 L2 P2 X10 Y20\nG0 X5\nG28.1\nG92 X0\nG55\n#100 = 1\n%\n",
    )
    .unwrap();
    let (code, _, err) = stanok(&["run", &first.display().to_string(), "--var", &var_s]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&var).unwrap();
    assert_eq!(value(&text, 5241), Some(10.0), "{text}");
    assert_eq!(value(&text, 5161), Some(5.0));
    assert_eq!(value(&text, 5210), Some(1.0));
    assert_eq!(value(&text, 5211), Some(5.0));
    assert_eq!(value(&text, 5220), Some(2.0));
    // Run 2 starts where run 1 stopped: in G55 with the G92 offset, so X0 is machine 10 + 5.
    let second = d.join("second.ngc");
    std::fs::write(&second, "G0 X0\nG92.1\nM2\n").unwrap();
    let (code, out, err) = stanok(&["canon", &second.display().to_string(), "--var", &var_s]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("SET_G5X_OFFSET(2, 10.0000, 20.0000"), "{out}");
    assert!(out.contains("SET_G92_OFFSET(5.0000, 0.0000"), "{out}");
    let text = std::fs::read_to_string(&var).unwrap();
    assert_eq!(value(&text, 5210), Some(0.0), "{text}");
    assert_eq!(value(&text, 5211), Some(0.0));
    assert_eq!(value(&text, 5220), Some(1.0));
    assert_eq!(value(&text, 5241), Some(10.0));
}

#[test]
fn var_is_refused_for_axioma_and_other_files() {
    let d = dir();
    let nc = d.join("p.nc");
    std::fs::write(&nc, "G0 X1\nM30\n").unwrap();
    let var = d.join("x.var").display().to_string();
    let (code, _, err) = stanok(&["run", &nc.display().to_string(), "--var", &var]);
    assert_eq!(code, 2);
    assert!(err.contains("RS274/NGC"), "{err}");
    let ngc = d.join("p.ngc");
    std::fs::write(&ngc, "G0 X1\nM2\n").unwrap();
    let toml = d.join("x.toml").display().to_string();
    let (code, _, err) = stanok(&["run", &ngc.display().to_string(), "--var", &toml]);
    assert_eq!(code, 2);
    assert!(err.contains(".var"), "{err}");
}
