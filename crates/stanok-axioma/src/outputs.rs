//! G110 / G111: set / reset PLC outputs (spec axioma-3 §5, manual 10).
//!
//! ```text
//!   G110 [H<offset> | N<offset>] Q<i>=<address> … (i = 1…32, at most 32 per block)   → ON
//!   G111 …                                                                          → OFF
//!   Canon::DigitalOutput { index = 8·offset + address, on, synchronised: true }
//! ```
//! The offset is in bytes of the common PLC memory relative to the machine parameter's base, the
//! address is a bit number (bit = address mod 8 of byte offset + address/8), so the Canon index is
//! the bit number from the base: `8·offset + address` ([D] §5.3). Outputs switch with the start of
//! the block's motion without stopping the path ([D] A25): the commands are queued before the
//! block's motion with `synchronised: true`; in a block without motion they take effect in program
//! order. The offset letter is `H`, or a second `N` word after the block number (A24).
//!
//! Errors [D §5.3]: Q index outside 1…32, a repeated index, a non-integer or negative address or
//! offset, an address ≥ the configured number of outputs, G110 and G111 in one block.

use crate::ctx::Ctx;
use crate::words::Val;
use stanok_canon::{Canon, Diagnostic};
use stanok_syntax::ColSpan;

/// Validates the output words of a G110 (`on`) / G111 block and queues the commands.
pub(super) fn switch(
    cx: &mut Ctx<'_>,
    on: bool,
    q_words: &[(u8, Val)],
    at: ColSpan,
) -> Result<(), Diagnostic> {
    let code = if on { "G110" } else { "G111" };
    let offset = match (cx.words.take(b'H'), cx.words.take(b'N')) {
        (Some(_), Some(n)) => {
            return Err(cx.err(
                "axioma::output-offset-twice",
                format!("{code}: the output offset is written twice (H and N)"),
                n.span,
            ))
        }
        (Some(v), None) | (None, Some(v)) => cx.non_negative_integer(v, "the output offset")?,
        (None, None) => 0,
    };
    if q_words.is_empty() {
        return Err(cx.err(
            "axioma::output-without-address",
            format!("{code} needs at least one output address Q<i>=<address>"),
            at,
        ));
    }
    let mut seen = 0u64;
    for &(index, v) in q_words {
        if !(1..=32).contains(&index) {
            return Err(cx.err(
                "axioma::output-index",
                format!("{code}: Q{index}= — the parameter index must be 1 … 32"),
                v.span,
            ));
        }
        if seen & (1 << index) != 0 {
            return Err(cx.err(
                "axioma::output-index-repeated",
                format!("{code}: Q{index}= is written twice in this block"),
                v.span,
            ));
        }
        seen |= 1 << index;
        let address = cx.non_negative_integer(v, "an output address")?;
        let outputs = cx.fe.params.plc_outputs;
        if address >= outputs {
            return Err(cx
                .err(
                    "axioma::output-address-range",
                    format!("{code}: output address {address} does not exist"),
                    v.span,
                )
                .with_note(format!(
                    "this machine has {outputs} outputs: addresses 0 … {}",
                    outputs.saturating_sub(1)
                )));
        }
        let index = (offset as u64 * 8 + address as u64).min(u32::MAX as u64) as u32;
        cx.out.push(Canon::DigitalOutput {
            index,
            on,
            synchronised: true,
        });
    }
    Ok(())
}
