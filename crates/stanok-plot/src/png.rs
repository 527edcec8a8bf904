//! The sheet as a PNG: the SVG rendered by resvg (usvg parses, tiny-skia rasterises).
//!
//! Text needs a font: the system's fonts are loaded once and the generic `sans-serif` family is
//! mapped to the first of DejaVu Sans, Liberation Sans, Noto Sans, Arial that is installed (else
//! to any installed family). Without any font the picture still renders, without its labels.

use resvg::{tiny_skia, usvg};
use std::sync::OnceLock;

/// Families tried for `sans-serif`, in order.
const SANS: [&str; 4] = ["DejaVu Sans", "Liberation Sans", "Noto Sans", "Arial"];

fn options() -> &'static usvg::Options<'static> {
    static OPTIONS: OnceLock<usvg::Options<'static>> = OnceLock::new();
    OPTIONS.get_or_init(|| {
        let mut opt = usvg::Options::default();
        let db = opt.fontdb_mut();
        db.load_system_fonts();
        let families: Vec<String> = db
            .faces()
            .flat_map(|f| f.families.iter().map(|(name, _)| name.clone()))
            .collect();
        let chosen = SANS
            .iter()
            .find(|want| families.iter().any(|f| f == *want))
            .map(|s| s.to_string())
            .or_else(|| families.first().cloned());
        if let Some(family) = chosen {
            db.set_sans_serif_family(family.clone());
            opt.font_family = family;
        }
        opt
    })
}

/// Renders an SVG document (as [`crate::Sheet::finish`] writes it) to PNG bytes at its own size.
pub fn render_png(svg: &str) -> Result<Vec<u8>, String> {
    let tree =
        usvg::Tree::from_str(svg, options()).map_err(|e| format!("cannot render the SVG: {e}"))?;
    let size = tree.size().to_int_size();
    let mut pixmap = tiny_skia::Pixmap::new(size.width(), size.height())
        .ok_or_else(|| format!("cannot make a {}×{} picture", size.width(), size.height()))?;
    pixmap.fill(tiny_skia::Color::WHITE);
    resvg::render(&tree, tiny_skia::Transform::default(), &mut pixmap.as_mut());
    pixmap
        .encode_png()
        .map_err(|e| format!("cannot encode the PNG: {e}"))
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_small_sheet_becomes_a_png_of_its_size() {
        let svg = crate::render_svg(
            &crate::tests::sample_program(),
            &crate::PlotOptions {
                width: 400,
                height: 300,
                ..Default::default()
            },
        );
        let png = super::render_png(&svg).unwrap();
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
        // IHDR: width and height, big-endian, at bytes 16..24.
        assert_eq!(u32::from_be_bytes(png[16..20].try_into().unwrap()), 400);
        assert_eq!(u32::from_be_bytes(png[20..24].try_into().unwrap()), 300);
        assert!(super::render_png("<not svg").is_err());
    }
}
