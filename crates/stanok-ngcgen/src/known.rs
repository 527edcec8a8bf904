//! The runner's recogniser of the listed differences between the standalone `rs274` and a real
//! LinuxCNC (docs/linuxcnc.md, "Known differences"): given a program's text, the name of the
//! difference it shows, if any. The runner asks only when the two traces differ.
//!
//! ## How a line is read
//! Each line is read as LinuxCNC reads its words: the comment dropped, lower case, blanks
//! removed, and everything inside brackets and parameter names (`#<…>`) blanked, so that an
//! expression such as `[EXP[-8.6]]` or a name such as `#<x>` holds no letter word. An `O…` line
//! (sub, call, if, while …) has no words at all. What is left are the letter words of the block
//! (`g43.1`, `z8.23`, `m61`, `q1` …), tested by their letters.
//!
//! ## The stub's position
//! The standalone interpreter resynchronises its position from its canonical-command stub after
//! `M6`, `M61` and a probe (`G38.x`). The stub follows only the straight and arc moves it prints:
//! it has not seen a tool length offset (`G43`, `G43.1`, `G43.2`, `G49`) applied since the last
//! move, nor a spline (`G5`, `G5.1`, a `G5.2 … G5.3` NURBS, printed as `NURBS_FEED`). A program
//! shows the difference if such a code is followed by a resynchronising one with no move
//! between, in file order. A move is a block with an axis word that is not data: `G10`, `G92`,
//! `G52` and `G43.1` take axis words without moving. A subroutine call counts as a move unless the
//! subroutine is in the same text and none of its lines moves. File order stands in for
//! execution order, which these programs mostly keep.

/// One line's letter words, as described in the module comment.
struct Line {
    /// The words, compacted (`g43.1z8.23`); empty for an O-word line.
    words: String,
    /// The line in lower case, comment included (for parameter names such as `_current_tool`).
    raw: String,
}

impl Line {
    fn read(line: &str) -> Line {
        let raw = line.to_ascii_lowercase();
        let text = raw.split(['(', ';']).next().unwrap_or("");
        let mut words = String::with_capacity(text.len());
        let mut depth = 0usize;
        let mut in_name = false;
        for c in text.chars() {
            match c {
                '[' => depth += 1,
                ']' => depth = depth.saturating_sub(1),
                '<' if words.ends_with('#') => in_name = true,
                '>' if in_name => in_name = false,
                _ if depth > 0 || in_name || c.is_whitespace() => {}
                _ => words.push(c),
            }
        }
        // An O-word line: flow control, no letter words. (An N word may come first.)
        let body = words.trim_start_matches(|c: char| c == 'n' || c.is_ascii_digit() || c == '.');
        if body.starts_with('o') {
            words.clear();
        }
        Line { words, raw }
    }

    /// The code (`g43`, `m6`, `g10l1p1` …) stands in the line, not as the start of a longer number.
    fn has(&self, code: &str) -> bool {
        let l = &self.words;
        l.match_indices(code).any(|(i, _)| {
            !l[i + code.len()..].starts_with(|c: char| c.is_ascii_digit() || c == '.')
        })
    }

    fn contains(&self, code: &str) -> bool {
        self.words.contains(code)
    }

    /// The block moves the tool: an axis word in a block that does not take axis words as data.
    fn moves(&self) -> bool {
        let axis = self
            .words
            .contains(['x', 'y', 'z', 'a', 'b', 'c', 'u', 'v', 'w']);
        let data = self.has("g10")
            || self.has("g92")
            || self.has("g52")
            || self.contains("g43.1")
            || self.contains("g28.1")
            || self.contains("g30.1");
        axis && !data
    }

    fn m6(&self) -> bool {
        self.has("m6") || self.has("m06")
    }

    /// `M6`, `M61` or a probe: the standalone interpreter rereads its position from the stub.
    fn resynchronises(&self) -> bool {
        self.m6() || self.has("m61") || self.contains("g38")
    }

    /// A tool length offset change or a spline: the stub's position falls behind.
    fn leaves_stub_behind(&self) -> bool {
        self.contains("g43") || self.has("g49") || self.spline()
    }

    fn spline(&self) -> bool {
        self.has("g5") || self.contains("g5.1") || self.contains("g5.3")
    }

    /// The name of the subroutine this `O… call` line calls.
    fn called(&self) -> Option<String> {
        let raw = self.raw.split(['(', ';']).next().unwrap_or("");
        let at = raw.find("call")?;
        let o = raw[..at].rfind('o')?;
        Some(raw[o..at].split_whitespace().collect())
    }
}

/// Whether a subroutine's body, if it is in `lines`, is known not to move (no line of it moves).
fn sub_is_still(lines: &[Line], name: &str) -> bool {
    let start = lines.iter().position(|l| {
        let raw: String = l.raw.split_whitespace().collect();
        raw.starts_with(&format!("{name}sub"))
    });
    let Some(start) = start else {
        return false;
    };
    let end: String = format!("{name}endsub");
    lines[start + 1..]
        .iter()
        .take_while(|l| {
            let raw: String = l.raw.split_whitespace().collect();
            !raw.starts_with(&end)
        })
        .all(|l| !l.moves() && l.called().is_none())
}

/// A listed difference between the standalone rs274 and a real LinuxCNC: the name of the one the
/// program's text shows, if any (module comment).
pub fn known_difference(text: &str) -> Option<&'static str> {
    let lines: Vec<Line> = text.lines().map(Line::read).collect();
    let mut tool_loaded = false;
    let mut after_m61 = false;
    let mut offset_in_force = false;
    // A tool length offset changed (or a spline ran) since the last move: rs274's stub still has
    // the old position.
    let mut stub_behind = false;
    for l in &lines {
        let m6 = l.m6();
        if m6 && l.contains("g43") {
            return Some("T… M6 G43 in one block");
        }
        if !tool_loaded {
            // rs274's simulated tool changer starts with the tool of table slot 1 in the
            // spindle; LinuxCNC's (and Stanok's) spindle is empty until M6 or M61.
            let writes_slot_1 = ["g10l1p1", "g10l10p1", "g10l11p1"].iter().any(|c| l.has(c));
            let g43_loaded = l.has("g43") && !l.contains("h");
            if writes_slot_1 || g43_loaded || l.raw.contains("_current_pocket") {
                return Some("the spindle holds tool slot 1 at start");
            }
        }
        // After M61 the standalone rs274 leaves #<_current_tool>, #5400… and the offset G43
        // takes as they were; LinuxCNC (milltask) and Stanok take the declared tool's.
        let comp_from_tool = (l.has("g41") || l.has("g42")) && !l.contains("d");
        if after_m61
            && (l.raw.contains("_current_tool")
                || l.raw.contains("#540")
                || l.raw.contains("#541")
                || (l.has("g43") && !l.contains("h"))
                || comp_from_tool)
        {
            return Some("M61 leaves the tool data as it was");
        }
        after_m61 |= l.has("m61");
        // M6, M61 and probes resynchronise rs274's position from its stub, which has not seen a
        // tool length offset applied (or a spline) since the last move; milltask (and Stanok)
        // keep the program position.
        if stub_behind && l.resynchronises() {
            return Some("M6/M61 after a tool length offset change or a spline without a move");
        }
        let call_moves = l.called().is_some_and(|name| !sub_is_still(&lines, &name));
        if l.spline() {
            stub_behind = true;
        } else if l.moves() || call_moves {
            stub_behind = false;
        } else if l.leaves_stub_behind() {
            stub_behind = true;
        }
        // G20/G21 under a tool length offset: LinuxCNC keeps the offset's number, which then
        // means another length (its later G43.2, G53, G28/G30 use it); Stanok keeps the length.
        if offset_in_force && (l.has("g20") || l.has("g21")) {
            return Some("G20/G21 under a tool length offset");
        }
        if l.has("g49") {
            offset_in_force = false;
        }
        offset_in_force |= l.contains("g43");
        // M61 Q1 declares the tool rs274 believes loaded already: its state stays apart.
        tool_loaded |= m6 || (l.has("m61") && !l.has("q1"));
    }
    None
}

#[cfg(test)]
mod tests {
    use super::known_difference;

    const RESYNC: &str = "M6/M61 after a tool length offset change or a spline without a move";

    /// Seed 20261205, program 1282: a G10 with a Z word between G43.1 and M61 does not move.
    #[test]
    fn a_g10_between_the_offset_and_m61_is_no_move() {
        let text =
            "F451.963\nG43.1 Z8.23\nG10 L1 P2 Z-1.\nM61 Q1 ; note\no<s100> call [1] [2] [3]\nM2\n";
        assert_eq!(known_difference(text), Some(RESYNC));
    }

    /// Seed 20261203, program 375: an expression with EXP (an x inside brackets) is no move.
    #[test]
    fn letters_inside_brackets_and_names_are_no_words() {
        let text = "G43.2H1\n#<_glob>=[EXP[-8.673]]\n#<x>=1\nG10L11P10Z+1\nM61Q10\nG0 X1\nM2\n";
        assert_eq!(known_difference(text), Some(RESYNC));
    }

    /// Seed 20261205, program 3221: a probe after a spline resynchronises from the stub too.
    #[test]
    fn a_probe_after_a_spline_resynchronises() {
        let text = "F42.2047\nG5.1 Y-0.6465 I0.0812 J0.0472\nG38.5 Z-0.1181\nG0\nM2\n";
        assert_eq!(known_difference(text), Some(RESYNC));
    }

    #[test]
    fn a_move_between_clears_it() {
        let text = "G43.1 Z8.23\nG1 X1 F100\nM61 Q1\nG0 X0\nM2\n";
        assert_eq!(known_difference(text), None);
        let text = "G43.1 Z8.23\nX1\nM61 Q2\nM2\n";
        assert_eq!(known_difference(text), None);
        // The offset and the move in one block: the move comes after the offset.
        let text = "G43 H1 G0 Z5\nM61 Q2\nM2\n";
        assert_eq!(known_difference(text), None);
    }

    #[test]
    fn a_call_moves_unless_its_body_is_in_the_text_and_still() {
        let moving = "o100 sub\nG0 X1\no100 endsub\nG43.1 Z1\no100 call\nM61 Q2\nM2\n";
        assert_eq!(known_difference(moving), None);
        let elsewhere = "G43.1 Z1\no<s100> call\nM61 Q2\nM2\n";
        assert_eq!(known_difference(elsewhere), None);
        let still = "o100 sub\n#1=2\no100 endsub\nG43.1 Z1\no100 call\nM61 Q2\nM2\n";
        assert_eq!(known_difference(still), Some(RESYNC));
    }
}
