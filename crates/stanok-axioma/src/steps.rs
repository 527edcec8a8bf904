//! The steps of one AxiOMA block, in the order `execute` (lib.rs) runs them: the words beyond
//! letters, the G codes sorted by group, then the manual's steps 1–7 (spec axioma-2 §4.1).

use super::*;

/// Keywords, in the written order.
pub(crate) fn read_keywords(cx: &mut Ctx<'_>, x: &mut ExtraWords) -> Result<(), Diagnostic> {
    let (cr, tech, sw, x_words3) = (&mut x.cr, &mut x.tech, &mut x.sw, &mut x.words3);
    for i in 0..cx.words.keywords.len() {
        let (kw, index, val, span) = cx.words.keywords[i];
        match kw {
            // §3.5: the profile applies from this block on (A25).
            Keyword::Brisk | Keyword::Soft => {
                let soft = kw == Keyword::Soft;
                cx.st.soft_acceleration = soft;
                cx.out.push(Canon::SetAccelerationProfile {
                    profile: if soft {
                        stanok_canon::AccelerationProfile::Soft
                    } else {
                        stanok_canon::AccelerationProfile::Brisk
                    },
                });
            }
            k if TechWords::handles(k) => tech.take(cx, k, index, val, span)?,
            Keyword::Aspline => sw.keyword = Some((SplineKind::Akima, span)),
            Keyword::Cspline => sw.keyword = Some((SplineKind::Cubic, span)),
            Keyword::Bspline => sw.keyword = Some((SplineKind::Nurbs, span)),
            Keyword::Splbreak => {
                comp3d::forbidden(cx, "SPLBREAK", span)?;
                sw.splbreak = true
            }
            Keyword::Pw | Keyword::Pl | Keyword::Sd => {
                let Some(v) = val else {
                    return Err(cx.err("interp::missing-value", "the word has no value", span));
                };
                match kw {
                    Keyword::Pw => sw.weight = Some(v),
                    Keyword::Pl => sw.increment = Some(v),
                    _ => sw.degree = Some(v),
                }
            }
            Keyword::Traori
            | Keyword::TrafOff
            | Keyword::OriEuler
            | Keyword::OriRpy
            | Keyword::OriAxes
            | Keyword::OriVect
            | Keyword::OriWks
            | Keyword::OriMks => {
                comp3d::forbidden(cx, cx.block.slice(span), span)?;
                orientation::keyword(cx, kw, span)?
            }
            Keyword::Cut2df
            | Keyword::Cut3dc
            | Keyword::Cut3dcc
            | Keyword::Cut3dccd
            | Keyword::Cut3df
            | Keyword::Cut3dfs
            | Keyword::Cut3dff => {
                comp3d::mode_word(cx, kw, span)?;
            }
            Keyword::Isd => {
                let Some(v) = val else {
                    return Err(cx.err("interp::missing-value", "ISD= has no value", span));
                };
                x_words3.isd = Some(v);
            }
            Keyword::Cr => {
                *cr = val;
                if cr.is_none() {
                    return Err(cx.err("interp::missing-value", "CR= has no value", span));
                }
            }
            Keyword::Lead | Keyword::Tilt => {
                // The manual names LEAD and TILT but describes them nowhere (spec axioma-4 §1.2).
                return Err(unsupported(cx, cx.block.slice(span), "LEAD/TILT", span));
            }
            _ => {
                return Err(unsupported(
                    cx,
                    cx.block.slice(span),
                    "keywords of other controls",
                    span,
                ))
            }
        }
    }
    Ok(())
}

/// Extended addresses: S2=… (speed of spindle 2), T2=/D2=, Q<i>=, N1=/H1=, orientation words;
/// the others come with later issues.
pub(crate) fn read_indexed(cx: &mut Ctx<'_>, x: &mut ExtraWords) -> Result<(), Diagnostic> {
    for &(letter, index, val) in &cx.words.indexed {
        if x.ori_words.take(letter, index, val) || x.words3.take(letter, index, val) {
            continue;
        }
        match letter {
            b'Q' => x.q_words.push((index, val)),
            b'N' | b'H'
                if index == 1 && cx.words.m.iter().any(|m| matches!(m.0, 902 | 903 | 905)) =>
            {
                x.m905_depth = Some(val)
            }
            b'S' if (1..=4).contains(&index) => x.indexed_speeds.push((index - 1, val.v)),
            // `T2=10`, `D3=2`: tool and edge of spindle 2…4 (spec axioma-2 §3.9–§3.10).
            b'T' if (2..=4).contains(&index) => x.spindle_tools.push((index - 1, val)),
            b'D' if (2..=4).contains(&index) => x.spindle_edges.push((index - 1, val)),
            _ => {
                return Err(unsupported(
                    cx,
                    &format!("{}{}=", letter as char, index),
                    "extended addresses",
                    val.span,
                ))
            }
        }
    }

    Ok(())
}

/// G codes: last of a group wins (with a warning), per the manual; one of G110/G111; no
/// interpolation code beside a cycle code.
pub(crate) fn sort_g_codes(cx: &mut Ctx<'_>) -> Result<Actions, Diagnostic> {
    let mut actions: Actions = Vec::with_capacity(cx.words.g.len());
    for &(code, span) in &cx.words.g {
        let Some(c) = g_code(code) else {
            return Err(cx.err(
                "axioma::unknown-g-code",
                format!("unknown G function G{}", code as f64 / 10.0),
                span,
            ));
        };
        let a = c.handler;
        if let (GAction::Output(_), Some((_, prev, _))) = (
            a,
            actions
                .iter()
                .find(|(b, _, _)| matches!(b, GAction::Output(_))),
        ) {
            return Err(cx.err(
                "axioma::outputs-twice",
                format!(
                    "only one of G110/G111 per block ({} is already programmed)",
                    g_name(*prev)
                ),
                span,
            ));
        }
        if let Some(pos) = actions
            .iter()
            .position(|(_, prev, _)| group_of(*prev) == Some(c.group))
        {
            let prev = actions.remove(pos);
            cx.warnings.push(Diagnostic::warning(
                "axioma::conflicting-words",
                format!(
                    "{} and {} exclude each other: only the last one takes effect",
                    g_name(prev.1),
                    g_name(code)
                ),
                cx.block.span_of(span),
            ));
        }
        actions.push((a, code, span));
    }

    let has_cycle_g = actions
        .iter()
        .any(|(a, _, _)| matches!(a, GAction::Cycle(_)));
    if let (true, Some((_, code, span))) = (
        has_cycle_g,
        actions
            .iter()
            .find(|(a, _, _)| matches!(a, GAction::Motion(_))),
    ) {
        return Err(cx.err(
            "axioma::cycle-and-interpolation",
            format!(
                "{} and a canned cycle in one block: the cycle would be activated and cancelled at once",
                g_name(*code)
            ),
            *span,
        ));
    }
    Ok(actions)
}

/// Step 1: The block's message (`MSG`), or one an HLL statement left for it.
pub(crate) fn message(cx: &mut Ctx<'_>) {
    let text = match cx.block.message {
        Some(text) => Some(cx.block.slice(text).to_string()),
        None => cx.fe.message.take(),
    };
    if let Some(text) = text.and_then(|t| message::displayed(cx, t)) {
        cx.out.push(Canon::Message { text });
    }
}

/// Step 2: Modal G codes: planes, units, distance modes, feed type, path mode, CSS, retract,
/// compensation selection, cycle activation; frame codes are refused under compensation.
pub(crate) fn modal_codes(
    cx: &mut Ctx<'_>,
    actions: &Actions,
    comp_active: bool,
) -> Result<Modal, Diagnostic> {
    let mut motion_code: Option<(MotionMode, ColSpan)> = None;
    let mut dwell: Option<ColSpan> = None;
    for &(a, _code, span) in actions {
        match a {
            GAction::Motion(m) => {
                motion_code = Some((m, span));
                // Tested first: a write journals the probe state, and G75 is rarely on.
                if cx.fe.probe.g75 {
                    cx.fe.probe.g75 = false;
                }
            }
            GAction::Probe => {
                motion_code = Some((MotionMode::Linear, span));
                cx.fe.probe.g75 = true;
            }
            GAction::Dwell => dwell = Some(span),
            GAction::Plane(_) | GAction::Workpiece(_) | GAction::LengthComp(_)
                if cx.fe.ext.comp3d.in_contour() =>
            {
                return Err(comp3d::forbidden(cx, &g_name(_code), span).unwrap_err());
            }
            GAction::Plane(p) if cx.st.plane != p => {
                if comp_active {
                    return Err(forbidden_under_comp(
                        cx,
                        "a plane change (G17/G18/G19)",
                        span,
                    ));
                }
                cx.out.push(Canon::SelectPlane { plane: p });
                cx.st.plane = p;
                polar::on_plane_change(cx);
            }
            GAction::Units(u) => {
                if cx.st.units != u {
                    cx.out.push(Canon::UseLengthUnits { units: u });
                }
                cx.st.units = u;
            }
            GAction::Distance(d) => cx.st.distance = d,
            GAction::ArcCentre(d) => cx.st.arc_distance = d,
            GAction::FeedMode(f) => {
                if cx.st.feed_mode != f {
                    // Spec axioma-2 §3.3 / A22: a real change of feed type resets F.
                    cx.st.feed = 0.0;
                    cx.st.feed_mode = f;
                    cx.out.push(Canon::SetFeedMode { mode: f });
                }
                if f == FeedMode::UnitsPerRevolution && cx.st.spindle_speed[0] <= 0.0 {
                    return Err(cx.manual(
                        615,
                        "G95 activated while the main spindle speed S is 0",
                        span,
                    ));
                }
            }
            GAction::PathMode(exact) => {
                // §3.4: G60 exact stop / G64 continuous path, carried by the planner.
                cx.st.path_mode = if exact {
                    PathMode::ExactStop
                } else {
                    PathMode::Continuous {
                        blend_tolerance: 0.0,
                    }
                };
                cx.out.push(Canon::SetPathMode {
                    mode: if exact {
                        stanok_canon::PathMode::ExactStop
                    } else {
                        stanok_canon::PathMode::Continuous { tolerance: 0.0 }
                    },
                    naive_cam_tolerance: None,
                });
            }
            GAction::Css(on) => technology::css_mode(cx, on),
            GAction::Retract(initial) => cx.st.retract_to_initial = initial,
            GAction::Radius(code) if cx.fe.ext.comp3d.claims(code) => {
                comp3d::select(cx, code, span)?
            }
            GAction::Radius(code) if cx.fe.ext.comp3d.phase != comp3d::Phase::Off => {
                return Err(comp3d::forbidden(cx, &g_name(code), span)
                    .err()
                    .unwrap_or_else(|| {
                        cx.err(
                            "axioma::cut3d-forbidden",
                            format!("{} while 3D compensation is on", g_name(code)),
                            span,
                        )
                    }));
            }
            GAction::Radius(code) => Comp::select(cx, code, span)?,
            GAction::CycleCancel => cx.fe.cycle.active = None,
            GAction::Cycle(kind) => cycles::activate(cx, kind),
            GAction::ZeroOffset(_)
            | GAction::Workpiece(_)
            | GAction::Shift(G194 | G195)
            | GAction::Mirror(_)
            | GAction::Scale(_)
            | GAction::Rotate(_)
                if comp_active =>
            {
                return Err(forbidden_under_comp(cx, &g_name(_code), span));
            }
            _ => {}
        }
    }
    Ok(Modal { motion_code, dwell })
}

/// Splines: mode changes and break points (§2.4.1, A16) before anything of this block moves.
pub(crate) fn spline_modes(
    cx: &mut Ctx<'_>,
    actions: &Actions,
    sw: &SplineWords,
    dwell: Option<ColSpan>,
) -> Result<(), Diagnostic> {
    let other_motion = actions.iter().any(|(a, _, _)| {
        matches!(
            a,
            GAction::Motion(_) | GAction::Probe | GAction::Home(_) | GAction::Cycle(_)
        )
    });
    let breaks = !cx.words.m.is_empty()
        || dwell.is_some()
        || actions.iter().any(|(a, _, _)| {
            matches!(
                a,
                GAction::ZeroOffset(_)
                    | GAction::Workpiece(_)
                    | GAction::Shift(_)
                    | GAction::Mirror(_)
                    | GAction::Scale(_)
                    | GAction::Rotate(_)
                    | GAction::Polar(_)
                    | GAction::Plane(_)
            )
        })
        || (cx.fe.ext.spline.kind == Some(SplineKind::Nurbs) && cx.words.any(b"TD"));
    splines::before_motion(cx, sw, other_motion, breaks)
}

/// An interpolation code cancels the cycle (§6.3); Q words go to G110/G111 or the cycle.
/// Returns the output switch (G110/G111) for step 6.
pub(crate) fn cycle_and_outputs(
    cx: &mut Ctx<'_>,
    actions: &Actions,
    modal: &Modal,
    q_words: &[(u8, Val)],
) -> Result<Option<(bool, ColSpan)>, Diagnostic> {
    // Tested first: writing journals the cycle state (its Q words), and most blocks have none.
    if modal.motion_code.is_some() && cx.fe.cycle.active.is_some() {
        cx.fe.cycle.active = None;
    }
    let output = actions.iter().find_map(|&(a, _, span)| match a {
        GAction::Output(on) => Some((on, span)),
        _ => None,
    });
    if output.is_none() && !q_words.is_empty() {
        if cx.fe.cycle.active.is_none() {
            let (i, v) = q_words[0];
            return Err(cx
                .err(
                    "axioma::q-without-cycle",
                    format!("Q{i}= has no meaning here: no canned cycle is active"),
                    v.span,
                )
                .with_note(
                    "cycle parameters follow a cycle G code (G81 … G389); outputs need G110/G111",
                ));
        }
        cycles::set_params(cx, q_words)?;
    }

    Ok(output)
}

/// Step 2b: Frames and offsets, in the manual's fixed order whatever the order of the words. A block
/// that programs mirror, scale, rotation, a shift or G10 takes its X/Y/Z as parameters: no
/// motion (returns whether it is such a parameter block).
pub(crate) fn frames_and_offsets(cx: &mut Ctx<'_>, actions: &Actions) -> Result<bool, Diagnostic> {
    let mut parameter_block = false;
    let mut frame_changed = false;
    let frame_functions = actions
        .iter()
        .filter(|(a, _, _)| {
            matches!(
                a,
                GAction::Mirror(true) | GAction::Scale(true) | GAction::Rotate(true)
            )
        })
        .count();
    frames::block_rules(cx, actions)?;
    if frame_functions > 1 {
        let (_, _, span) = actions[actions.len() - 1];
        return Err(cx.err(
            "axioma::frames-in-one-block",
            "G73, G173 and G273 must each be programmed in a block of its own",
            span,
        ));
    }
    for &(a, code, span) in actions {
        match a {
            GAction::ZeroOffset(s) => frames::zero_offset(cx, s)?,
            GAction::Workpiece(s) => frames::workpiece(cx, s)?,
            GAction::Mirror(on) => frames::mirror(cx, on)?,
            GAction::Scale(on) => frames::scale(cx, on)?,
            GAction::Rotate(on) => frames::rotate(cx, on)?,
            GAction::Shift(code) => frames::shift(cx, code)?,
            GAction::Diameter => {
                frames::diameter_mode(cx, span)?;
                parameter_block = true;
                continue;
            }
            GAction::LengthComp(code) => {
                tools::length_comp(cx, code)?;
                continue;
            }
            GAction::Polar(on) => {
                if on {
                    polar::g16(cx)?;
                    parameter_block = true;
                } else {
                    cx.fe.modes.polar.on = false;
                }
                continue;
            }
            _ => continue,
        }
        frame_changed = true;
        parameter_block |= matches!(
            a,
            GAction::Mirror(true) | GAction::Scale(true) | GAction::Rotate(true)
        ) || matches!(a, GAction::Shift(c) if c != G193);
        let _ = code;
    }
    if frame_changed {
        frames::apply(cx);
    }
    Ok(parameter_block)
}

/// Step 3: F (a constant, an expression or FTABLE(i), §3.1).
pub(crate) fn feed(cx: &mut Ctx<'_>, tech: &TechWords) -> Result<(), Diagnostic> {
    if let Some(f) = cx.words.take(b'F').or(tech.feed) {
        if f.v < 0.0 {
            return Err(cx.err("axioma::negative-feed", "negative feed F", f.span));
        }
        cx.st.feed = match cx.st.feed_mode {
            FeedMode::InverseTime => f.v,
            _ => cx.mm(f.v),
        };
        cx.out.push(Canon::SetFeedRate { feed: cx.st.feed });
    }

    Ok(())
}

/// Steps 4/5: S and T without an M function, then the prefix M functions by group order (spindle
/// with its S, coolant, tool with its T, the other groups), then the other spindles' tools.
pub(crate) fn prefix_aux(
    cx: &mut Ctx<'_>,
    actions: &Actions,
    x: &ExtraWords,
    comp_active: bool,
) -> Result<Aux, Diagnostic> {
    let tech = &x.tech;
    let table = &cx.fe.params.m_table;
    let mut ms: Vec<(MFunction, ColSpan)> = Vec::with_capacity(cx.words.m.len());
    for &(number, span) in &cx.words.m {
        // §13.2.3: no M function inside a 3D-compensated contour; the program end ends it.
        if !m_function(table, number).is_some_and(|f| {
            matches!(
                f.kind,
                MKind::ProgramEnd | MKind::ProgramEndToWaitingPosition
            )
        }) {
            comp3d::forbidden(cx, &format!("M{number}"), span)?;
        }
        let Some(f) = m_function(table, number) else {
            return Err(cx.err(
                "axioma::unknown-m-function",
                format!(
                    "M{number} is not in the M-function table of this machine (profile `{}`)",
                    table.profile
                ),
                span,
            ));
        };
        ms.push((f, span));
    }
    // Stable sort: same group order keeps the table's group order, then the written order.
    ms.sort_by_key(|(f, _)| f.order);
    let mut mw = MWords::default();
    mw.speed[0] = cx.words.take(b'S').or(tech.speed[0]);
    for &(spindle, v) in &x.indexed_speeds {
        mw.speed[spindle as usize] = Some(Val {
            v,
            span: cx.whole(),
        });
    }
    for (s, v) in tech.speed.iter().enumerate().skip(1) {
        if v.is_some() {
            mw.speed[s] = *v;
        }
    }
    let t_word = cx.words.take(b'T');
    let tool = match t_word {
        Some(t) => Some(cx.non_negative_integer(t, "tool number T")?),
        None => None,
    };
    if let Some(t) = tool {
        if t > 32767 {
            return Err(cx.err(
                "axioma::tool-number",
                format!("T{t}: tool numbers are 0 … 32767"),
                t_word.map(|v| v.span).unwrap_or_else(|| cx.whole()),
            ));
        }
    }
    mw.tool = tool;
    if let (Some(t), true) = (tool, comp_active) {
        // A5: T0 (with M06) suspends compensation and is allowed; another tool is not.
        if t != 0 {
            let at = t_word.map(|v| v.span).unwrap_or_else(|| cx.whole());
            return Err(forbidden_under_comp(cx, "a T word (new tool radius)", at));
        }
    }
    if let Some(&(_, span)) = cx.words.m.iter().find(|m| m.0 == 905) {
        let depth = x.m905_depth.map(|v| v.v);
        Comp::set_depth(cx, depth, x.m905_depth.map(|v| v.span).unwrap_or(span))?;
    } else {
        mw.spindle_param = x.m905_depth;
    }
    let has_tool_m = ms.iter().any(|(f, _)| f.kind == MKind::ToolChange);
    let d_word = cx.words.take(b'D');
    if let (Some(d), false) = (d_word, has_tool_m) {
        return Err(tools::stray_d(cx, d));
    }
    mw.edge = d_word;
    if let (Some(&(_, v)), false) = (
        x.spindle_tools.first().or(x.spindle_edges.first()),
        has_tool_m,
    ) {
        return Err(cx.err(
            "axioma::spindle-tool-without-change",
            "T<spindle>= and D<spindle>= act only together with M06 or M66",
            v.span,
        ));
    }

    technology::limits(cx, tech)?;
    // An S whose spindle has no spindle function in this block is stored now (§3.7).
    for spindle in 0..4u8 {
        let with_m = ms.iter().any(|(f, _)| f.spindle() == Some(spindle));
        if let (Some(v), false) = (mw.speed[spindle as usize], with_m) {
            set_speed(cx, spindle, v)?;
            mw.speed_done[spindle as usize] = true;
        }
    }
    // G96 needs a cutting speed: stored earlier, stored just above, or this block's S that its
    // spindle function (`G96 S100 M3`, issue 22 item 2) sets below.
    if let (Some((_, _, span)), false) = (
        actions
            .iter()
            .find(|(a, _, _)| matches!(a, GAction::Css(true))),
        mw.speed.iter().any(Option::is_some),
    ) {
        technology::check_css_speed(cx, *span)?;
    }
    technology::refresh(cx);
    if let (Some(t), false) = (tool, has_tool_m) {
        cx.st.selected_tool = Some(t);
        cx.out.push(Canon::SelectTool { tool: t });
        mw.tool_done = true;
    }
    for (f, span) in ms.iter().filter(|(f, _)| f.timing == AuxTiming::Prefix) {
        run_m(cx, f, &mut mw, *span)?;
    }
    // Tools of spindles 2…4 after the main spindle's change (manual §6.10: "T2 in the first spindle
    // and T3 in the second").
    if has_tool_m {
        tools::other_spindles(cx, &x.spindle_tools, &x.spindle_edges)?;
    }

    // Tool length: a changed σ·V is applied by this block's motion, or the next one's.
    tools::update(cx);
    Ok(Aux { ms, mw })
}

/// Step 6: G04 dwell, a cycle call, G28/G29, or the block's motion (orientation, spline point, probe
/// move, line or arc); a parameter block only takes its motion code.
pub(crate) fn dwell_or_motion(
    cx: &mut Ctx<'_>,
    actions: &Actions,
    x: &ExtraWords,
    modal: &Modal,
    parameter_block: bool,
    comp_active: bool,
) -> Result<(), Diagnostic> {
    let (motion_code, dwell) = (modal.motion_code, modal.dwell);
    let home = actions.iter().find_map(|&(a, _, span)| match a {
        GAction::Home(to) => Some((to, span)),
        _ => None,
    });
    if let Some(span) = dwell {
        dwell_block(cx, span)?;
    } else if let (Some((_, span)), true) = (home, comp_active) {
        return Err(forbidden_under_comp(cx, "G28/G29", span));
    } else if cx.fe.cycle.active.is_some() && cx.has_axis_words() && !parameter_block {
        if let Some((m, _)) = motion_code {
            cx.st.motion = m;
        }
        if cx.st.feed_mode == FeedMode::InverseTime {
            return Err(cx.manual(
                617,
                "G93 (inverse time) is not allowed in canned cycles",
                cx.whole(),
            ));
        }
        cycles::call(cx, cx.whole())?;
    } else if let Some((to_home, span)) = home {
        if to_home {
            home::g28(cx, span)?;
        } else {
            home::g29(cx, span)?;
        }
    } else if parameter_block {
        if let Some((m, _)) = motion_code {
            cx.st.motion = m;
        }
    } else {
        if let Some((m, _)) = motion_code {
            cx.st.motion = m;
        }
        let at = motion_code.map(|m| m.1).unwrap_or_else(|| cx.whole());
        let monitored = cx.fe.probe.g75
            || (cx.fe.ext.m.batch_probe
                && cx.st.motion == MotionMode::Linear
                && !cx.fe.modes.polar.on);
        let generalized = orientation::check(cx, &x.ori_words)?;
        comp3d::before_motion(cx, &x.words3, generalized)?;
        if generalized {
            orientation::motion(cx, at, &x.ori_words)?;
        } else if cx.fe.ext.spline.kind.is_some() {
            splines::point(cx, at, &x.sw)?;
        } else if monitored {
            probe::probe_move(cx, at)?;
        } else {
            motion(cx, at, x.cr)?;
        }
    }
    Ok(())
}

/// Step 7: Postfix M functions by group order, program control (M02/M30 …) last; speeds of spindles
/// whose M function ran neither before nor now; compensation's end of block.
pub(crate) fn postfix_aux(cx: &mut Ctx<'_>, aux: &mut Aux) -> Result<Outcome, Diagnostic> {
    let Aux { ms, mw } = aux;
    let mut outcome = Outcome::Continue;
    for (f, span) in ms.iter().filter(|(f, _)| f.timing == AuxTiming::Postfix) {
        if matches!(
            f.kind,
            MKind::ProgramEnd | MKind::ProgramEndToWaitingPosition
        ) {
            outcome = Outcome::End;
        }
        debug_assert!(!f.is_program_control() || f.timing == AuxTiming::Postfix);
        run_m(cx, f, mw, *span)?;
    }
    for spindle in 0..4u8 {
        if let (Some(v), false) = (mw.speed[spindle as usize], mw.speed_done[spindle as usize]) {
            set_speed(cx, spindle, v)?;
        }
    }
    Comp::end_of_block(cx)?;
    Ok(outcome)
}
