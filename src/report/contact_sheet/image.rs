//! A plain 8-bit RGB image and its PNG encoding.

/// An 8-bit sRGB image, rows top to bottom, 3 bytes per pixel.
///
/// ```
/// use facebem::report::contact_sheet::RgbImage;
/// let mut img = RgbImage::new(4, 2, [255, 255, 255]);
/// img.put(3, 1, [10, 20, 30]);
/// assert_eq!(img.get(3, 1), [10, 20, 30]);
/// assert_eq!(img.get(0, 0), [255, 255, 255]);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RgbImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `3 · width · height` bytes, row-major, R G B.
    pub pixels: Vec<u8>,
}

impl RgbImage {
    /// An image filled with `fill`.
    pub fn new(width: u32, height: u32, fill: [u8; 3]) -> RgbImage {
        let n = width as usize * height as usize;
        let mut pixels = Vec::with_capacity(3 * n);
        for _ in 0..n {
            pixels.extend_from_slice(&fill);
        }
        RgbImage {
            width,
            height,
            pixels,
        }
    }

    fn offset(&self, x: u32, y: u32) -> usize {
        3 * (y as usize * self.width as usize + x as usize)
    }

    /// The pixel at (`x`, `y`); panics outside the image (a programming error).
    pub fn get(&self, x: u32, y: u32) -> [u8; 3] {
        let o = self.offset(x, y);
        [self.pixels[o], self.pixels[o + 1], self.pixels[o + 2]]
    }

    /// Sets the pixel at (`x`, `y`); ignored outside the image (clipping for text and boxes).
    pub fn put(&mut self, x: u32, y: u32, rgb: [u8; 3]) {
        if x < self.width && y < self.height {
            let o = self.offset(x, y);
            self.pixels[o..o + 3].copy_from_slice(&rgb);
        }
    }

    /// Fills the rectangle `[x, x + w) × [y, y + h)` (clipped).
    pub fn fill_rect(&mut self, x: u32, y: u32, w: u32, h: u32, rgb: [u8; 3]) {
        for yy in y..y.saturating_add(h).min(self.height) {
            for xx in x..x.saturating_add(w).min(self.width) {
                self.put(xx, yy, rgb);
            }
        }
    }

    /// Copies `src` with its top-left corner at (`x`, `y`) (clipped).
    pub fn blit(&mut self, src: &RgbImage, x: u32, y: u32) {
        for sy in 0..src.height {
            for sx in 0..src.width {
                self.put(x + sx, y + sy, src.get(sx, sy));
            }
        }
    }

    /// Encodes the image as an 8-bit RGB PNG.
    pub fn to_png(&self) -> Result<Vec<u8>, png::EncodingError> {
        let mut out = Vec::new();
        {
            let mut encoder = png::Encoder::new(&mut out, self.width, self.height);
            encoder.set_color(png::ColorType::Rgb);
            encoder.set_depth(png::BitDepth::Eight);
            encoder.set_compression(png::Compression::Balanced);
            let mut writer = encoder.write_header()?;
            writer.write_image_data(&self.pixels)?;
            writer.finish()?;
        }
        Ok(out)
    }
}
