//! Labels in the public-domain 8×8 IBM VGA bitmap font (crate `font8x8`), scaled by integer
//! factors. ASCII only; other characters are drawn as `?`.

use font8x8::legacy::BASIC_LEGACY;

use super::image::RgbImage;

/// Glyph cell size of the font at scale 1, in pixels.
pub const GLYPH_PX: u32 = 8;

/// Width in pixels of `text` at `scale`.
pub fn text_width(text: &str, scale: u32) -> u32 {
    text.chars().count() as u32 * GLYPH_PX * scale
}

/// `text` shortened with a trailing `~` so that it fits in `max_px` at `scale`.
pub fn fit(text: &str, scale: u32, max_px: u32) -> String {
    let max_chars = (max_px / (GLYPH_PX * scale.max(1))) as usize;
    if text.chars().count() <= max_chars {
        return text.to_string();
    }
    let mut s: String = text.chars().take(max_chars.saturating_sub(1)).collect();
    s.push('~');
    s
}

/// Draws `text` with its top-left corner at (`x`, `y`), each font pixel a `scale × scale` block.
pub fn draw_text(img: &mut RgbImage, x: u32, y: u32, text: &str, scale: u32, rgb: [u8; 3]) {
    let scale = scale.max(1);
    for (i, ch) in text.chars().enumerate() {
        let code = if ch.is_ascii() && !ch.is_ascii_control() {
            ch as usize
        } else {
            '?' as usize
        };
        let glyph = BASIC_LEGACY[code];
        let gx = x + i as u32 * GLYPH_PX * scale;
        for (row, bits) in glyph.iter().enumerate() {
            for col in 0..GLYPH_PX {
                // The least significant bit is the leftmost pixel.
                if bits >> col & 1 == 1 {
                    img.fill_rect(gx + col * scale, y + row as u32 * scale, scale, scale, rgb);
                }
            }
        }
    }
}
