//! The panel's manual modes in headless Chromium: jog by increments with the buttons and
//! continuously with the keyboard (arrows, Page Up/Down as in LinuxCNC's AXIS), MDI blocks typed
//! and run with Enter (the modes carry from block to block), touch-off, reference return, F1 and
//! Esc stop, digit keys set the feed override. Screenshot: `target/tmp/panel/manual.png`.

mod cdp;
mod common;
mod panel;
use panel::*;
use std::time::Duration;

#[test]
fn jog_mdi_touch_off_and_home_from_the_page_and_the_keyboard() {
    let panel = Panel::start("manual", &["--time-scale", "1"]);
    let Some(mut b) = open(&panel, "manual") else {
        return;
    };
    let settle = |b: &mut cdp::Browser| {
        b.wait_until(
            "['idle','finished','stopped','alarm'].some(s => document.getElementById('run-state').classList.contains(s))",
            Duration::from_secs(30),
        );
    };
    // Increments with the buttons.
    set_value(&mut b, "jog-speed", "3000");
    for (step, want) in [("1", 1.0), ("0.1", 1.1), ("0.01", 1.11), ("0.001", 1.111)] {
        set_value(&mut b, "jog-step", step);
        b.click("#jog-Xplus");
        b.wait_until(
            &format!("document.querySelector('tr[data-axis=\"X\"] .machine').textContent === '{want:.3}'"),
            Duration::from_secs(60),
        );
        settle(&mut b);
    }
    set_value(&mut b, "jog-step", "1");
    b.click("#jog-Zminus");
    b.wait_until(
        "document.querySelector('tr[data-axis=\"Z\"] .machine').textContent === '-1.000'",
        Duration::from_secs(60),
    );
    settle(&mut b);
    // Page Up: Z+ one increment.
    b.key("PageUp", true);
    b.key("PageUp", false);
    b.wait_until(
        "document.querySelector('tr[data-axis=\"Z\"] .machine').textContent === '0.000'",
        Duration::from_secs(60),
    );
    settle(&mut b);
    // Continuous with the keyboard: moves while → is held, stops when it is released.
    set_value(&mut b, "jog-step", "");
    set_value(&mut b, "jog-speed", "1200");
    let x0 = dro(&mut b)[0];
    b.key("ArrowRight", true);
    b.wait_until(
        "document.getElementById('run-state').classList.contains('jogging')",
        Duration::from_secs(30),
    );
    std::thread::sleep(Duration::from_millis(700));
    b.key("ArrowRight", false);
    settle(&mut b);
    let x1 = dro(&mut b)[0];
    assert!(x1 > x0 + 5.0 && x1 < x0 + 40.0, "{x0} → {x1}");
    std::thread::sleep(Duration::from_millis(300));
    assert_eq!(dro(&mut b)[0], x1, "stands after the key is released");
    // ↑ is Y+.
    b.key("ArrowUp", true);
    std::thread::sleep(Duration::from_millis(300));
    b.key("ArrowUp", false);
    settle(&mut b);
    assert!(dro(&mut b)[1] > 0.5);

    // Reference return: every axis at zero, referenced.
    b.click("#home-all");
    b.wait_until(
        "[...document.querySelectorAll('#dro .homed')].every(e => e.textContent === '●')",
        Duration::from_secs(30),
    );
    settle(&mut b);
    assert_eq!(dro(&mut b), [0.0, 0.0, 0.0]);

    // MDI: typed, run with Enter; the modes carry over (G91 stays).
    let mdi = |b: &mut cdp::Browser, text: &str| {
        set_value(b, "mdi-text", text);
        b.eval(
            "document.getElementById('mdi-text').dispatchEvent(new KeyboardEvent('keydown', {key: 'Enter', bubbles: true}))",
        );
        b.wait_until(
            &format!("document.querySelector('#mdi-history li') && document.querySelector('#mdi-history li').textContent === {}",
                serde_json::json!(text)),
            Duration::from_secs(60),
        );
    };
    set_value(&mut b, "dialect", "rs274ngc");
    mdi(&mut b, "G21 G90 G0 X10 Y5");
    b.wait_until(
        "document.querySelector('tr[data-axis=\"X\"] .machine').textContent === '10.000'",
        Duration::from_secs(60),
    );
    settle(&mut b);
    mdi(&mut b, "G91");
    mdi(&mut b, "G1 X2 F1200");
    b.wait_until(
        "document.querySelector('tr[data-axis=\"X\"] .machine').textContent === '12.000'",
        Duration::from_secs(60),
    );
    settle(&mut b);
    assert_eq!(dro(&mut b), [12.0, 5.0, 0.0]);
    assert!(b
        .eval("document.getElementById('g-codes').textContent")
        .as_str()
        .unwrap()
        .contains("G91"));
    // An MDI error: marked in the history, nothing moves.
    mdi(&mut b, "G1 X5 Q");
    assert_eq!(
        b.eval("document.querySelector('#mdi-history li').className"),
        "error"
    );
    assert!(b
        .eval("document.getElementById('manual-result').textContent")
        .as_str()
        .unwrap()
        .contains("Q"));
    assert_eq!(dro(&mut b), [12.0, 5.0, 0.0]);

    // Touch-off: X reads 0 here, Y reads 2.5.
    set_value(&mut b, "touch-axis", "X");
    set_value(&mut b, "touch-value", "0");
    b.click("#touch-off");
    b.wait_until(
        "document.querySelector('tr[data-axis=\"X\"] .work').textContent === '0.000'",
        Duration::from_secs(60),
    );
    set_value(&mut b, "touch-axis", "Y");
    set_value(&mut b, "touch-value", "2.5");
    b.click("#touch-off");
    b.wait_until(
        "document.querySelector('tr[data-axis=\"Y\"] .work').textContent === '2.500'",
        Duration::from_secs(60),
    );
    assert_eq!(dro(&mut b), [12.0, 5.0, 0.0], "touch-off moves nothing");
    // A program now runs in that frame: G54 X0 Y0 is machine X12 Y2.5.
    load_program(&mut b, "frame.ngc", "G21 G90 G54\nG0 X0 Y0\nM2\n");
    b.click("#cycle-start");
    wait_state(&mut b, "finished", 90);
    assert_eq!(dro(&mut b), [12.0, 2.5, 0.0]);
    assert_eq!(dro_of(&mut b, "work"), [0.0, 0.0, 0.0]);

    // Digit keys: feed override (5 → 50 %, ` → 0 %, 0 → 100 %).
    for (key, want) in [("5", "50 %"), ("`", "0 %"), ("0", "100 %")] {
        b.key(key, true);
        b.key(key, false);
        b.wait_until(
            &format!("document.getElementById('feed-override-value').textContent === '{want}'"),
            Duration::from_secs(30),
        );
    }
    // F1 and Esc stop a jog while its key is still held.
    set_value(&mut b, "jog-step", "");
    set_value(&mut b, "jog-speed", "600");
    for stop_key in ["F1", "Escape"] {
        b.key("ArrowDown", true);
        b.wait_until(
            "document.getElementById('run-state').classList.contains('jogging')",
            Duration::from_secs(30),
        );
        std::thread::sleep(Duration::from_millis(300));
        if stop_key == "F1" {
            shot(&mut b, "manual");
        }
        b.key(stop_key, true);
        b.key(stop_key, false);
        settle(&mut b);
        let y = dro(&mut b)[1];
        std::thread::sleep(Duration::from_millis(400));
        assert_eq!(dro(&mut b)[1], y, "{stop_key} stopped the jog");
        b.key("ArrowDown", false);
    }
    no_page_errors(&mut b);
}
