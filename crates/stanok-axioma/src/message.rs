//! MSG("…"): what the operator sees (spec axioma-1 §4).

use crate::ctx::Ctx;
use stanok_canon::Diagnostic;

/// The manual's MSG limits (spec axioma-1 §4, A28; issue 22 item 5): at most 256 characters —
/// a longer text is cut to 256 with a warning —, and only Latin text is displayed: a message with a
/// letter of another alphabet is accepted and not shown (the manual's behaviour), with a warning.
/// Latin letters are those of ASCII and the Latin blocks U+00C0…U+024F and U+1E00…U+1EFF; digits,
/// punctuation and symbols are neutral.
pub(super) fn displayed(cx: &mut Ctx<'_>, mut text: String) -> Option<String> {
    const MAX_CHARS: usize = 256;
    let latin = |c: char| {
        !c.is_alphabetic()
            || c.is_ascii()
            || ('\u{00C0}'..='\u{024F}').contains(&c)
            || ('\u{1E00}'..='\u{1EFF}').contains(&c)
    };
    if let Some(c) = text.chars().find(|&c| !latin(c)) {
        cx.warnings.push(
            Diagnostic::warning(
                "axioma::msg-not-latin",
                format!("MSG text with `{c}`, a letter outside the Latin alphabet: the control does not display it"),
                cx.block.span_of(cx.whole()),
            )
            .with_note("the manual: only Latin text is supported in messages"),
        );
        return None;
    }
    if let Some((cut, _)) = text.char_indices().nth(MAX_CHARS) {
        cx.warnings.push(
            Diagnostic::warning(
                "axioma::msg-too-long",
                format!(
                    "MSG text of {} characters: only the first {MAX_CHARS} are displayed",
                    text.chars().count()
                ),
                cx.block.span_of(cx.whole()),
            )
            .with_note("the manual: at most 256 characters"),
        );
        text.truncate(cut);
    }
    Some(text)
}
