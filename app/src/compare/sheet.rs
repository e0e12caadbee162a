//! The comparison sheet: the variants' pictures side by side under their names, and the metrics
//! table under them, one column per variant aligned with its picture and the row labels on the
//! left. Text is drawn with the bundled fonts ([`crate::annotate::text`]).

use image::{Rgba, RgbaImage};

use crate::annotate::text::{Face, TextPainter};
use crate::metrics::table::Row;

/// Largest sheet side in pixels; `cutaway compare` refuses sizes that would exceed it before
/// rendering anything.
pub const MAX_SIDE: u32 = 16384;

const BACKGROUND: Rgba<u8> = Rgba([255, 255, 255, 255]);
const STRIPE: Rgba<u8> = Rgba([240, 242, 245, 255]);
const INK: [u8; 4] = [30, 33, 38, 255];
const MUTED: [u8; 4] = [90, 96, 105, 255];

/// Sizes of the sheet's parts, all in pixels, derived from one picture's size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Layout {
    pub margin: u32,
    pub gap: u32,
    /// Text size of names and table.
    pub px: f32,
    pub title_height: u32,
    pub row_height: u32,
    pub label_width: u32,
    pub picture: [u32; 2],
    pub columns: u32,
    pub rows: u32,
}

impl Layout {
    /// The layout for `columns` pictures of `picture` size and `rows` table rows whose longest
    /// label is `label_chars` characters.
    pub fn new(picture: [u32; 2], columns: u32, rows: u32, label_chars: usize) -> Layout {
        let px = (picture[0] as f32 / 30.0).clamp(12.0, 22.0);
        let margin = (px * 0.9).round() as u32;
        Layout {
            margin,
            gap: margin,
            px,
            title_height: (px * 1.9).round() as u32,
            row_height: (px * 1.45).round() as u32,
            // A generous estimate so it never needs the font: 0.62 em per character.
            label_width: ((label_chars.max(8) as f32 * px * 0.62).ceil() as u32).min(600),
            picture,
            columns,
            rows,
        }
    }

    /// The whole sheet's size (as `u64`, so a request too large to draw can be refused first).
    pub fn size(&self) -> [u64; 2] {
        let columns = self.columns.max(1) as u64;
        let width = 2 * self.margin as u64
            + self.label_width as u64
            + columns * self.picture[0] as u64
            + (columns - 1) * self.gap as u64;
        let height = 2 * self.margin as u64
            + self.title_height as u64
            + self.picture[1] as u64
            + self.gap as u64
            + self.rows as u64 * self.row_height as u64;
        [width, height]
    }

    /// Left edge of column `k`'s picture.
    pub fn column_x(&self, k: u32) -> u32 {
        self.margin + self.label_width + k * (self.picture[0] + self.gap)
    }

    /// Top of the table.
    pub fn table_y(&self) -> u32 {
        self.margin + self.title_height + self.picture[1] + self.gap
    }
}

/// Draws the sheet: `pictures` (all of one size) titled by `names`, and `rows` under them.
/// Fails when the sheet would be larger than [`MAX_SIDE`] on a side.
pub fn draw(names: &[String], pictures: &[RgbaImage], rows: &[Row]) -> anyhow::Result<RgbaImage> {
    let picture = pictures.first().map_or([1, 1], |p| [p.width(), p.height()]);
    let label_chars = rows
        .iter()
        .map(|r| r.label.chars().count())
        .max()
        .unwrap_or(0);
    let layout = Layout::new(
        picture,
        pictures.len() as u32,
        rows.len() as u32,
        label_chars,
    );
    let [width, height] = layout.size();
    if width > MAX_SIDE as u64 || height > MAX_SIDE as u64 {
        anyhow::bail!(
            "the comparison sheet would be {width}×{height} pixels, more than {MAX_SIDE} on a side; use a smaller --width or --height"
        );
    }
    let mut sheet = RgbaImage::from_pixel(width as u32, height as u32, BACKGROUND);
    let text = TextPainter::new();
    let px = layout.px;
    let line = text.line_height(Face::Sans, px);
    for (k, (name, picture)) in names.iter().zip(pictures).enumerate() {
        let x = layout.column_x(k as u32);
        let title = fit(&text, Face::Sans, px * 1.1, name, picture.width() as f32);
        let title_x =
            x as f32 + (picture.width() as f32 - text.width(Face::Sans, px * 1.1, &title)) / 2.0;
        text.draw(
            &mut sheet,
            Face::Sans,
            px * 1.1,
            title_x,
            layout.margin as f32 + (layout.title_height as f32 - line * 1.1) / 2.0,
            &title,
            INK,
        );
        image::imageops::overlay(
            &mut sheet,
            picture,
            x as i64,
            (layout.margin + layout.title_height) as i64,
        );
    }
    let table_y = layout.table_y();
    for (r, row) in rows.iter().enumerate() {
        let y = table_y + r as u32 * layout.row_height;
        if r % 2 == 0 {
            for yy in y..(y + layout.row_height).min(sheet.height()) {
                for xx in layout.margin..sheet.width() - layout.margin {
                    sheet.put_pixel(xx, yy, STRIPE);
                }
            }
        }
        let top = y as f32 + (layout.row_height as f32 - line) / 2.0;
        let label = fit(
            &text,
            Face::Sans,
            px,
            &row.label,
            layout.label_width as f32 - px * 0.5,
        );
        text.draw(
            &mut sheet,
            Face::Sans,
            px,
            layout.margin as f32 + px * 0.3,
            top,
            &label,
            MUTED,
        );
        for (k, cell) in row.cells.iter().enumerate() {
            let x = layout.column_x(k as u32) as f32;
            let room = layout.picture[0] as f32 - px;
            let cell = fit(&text, Face::Mono, px, cell, room);
            let w = text.width(Face::Mono, px, &cell);
            // Centred under the column's picture.
            text.draw(
                &mut sheet,
                Face::Mono,
                px,
                x + (layout.picture[0] as f32 + w) / 2.0 - w,
                top,
                &cell,
                INK,
            );
        }
    }
    Ok(sheet)
}

/// `text` shortened with an ellipsis to fit `room` pixels.
fn fit(painter: &TextPainter, face: Face, px: f32, text: &str, room: f32) -> String {
    if painter.width(face, px, text) <= room {
        return text.to_string();
    }
    let mut chars: Vec<char> = text.chars().collect();
    while !chars.is_empty() {
        chars.pop();
        let candidate: String = chars.iter().collect::<String>() + "…";
        if painter.width(face, px, &candidate) <= room {
            return candidate;
        }
    }
    String::new()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn solid(color: [u8; 4]) -> RgbaImage {
        RgbaImage::from_pixel(200, 150, Rgba(color))
    }

    #[test]
    fn pictures_sit_side_by_side_and_the_table_under_them() {
        let names = vec!["straight".to_string(), "wedge".to_string()];
        let pictures = vec![solid([255, 0, 0, 255]), solid([0, 0, 255, 255])];
        let rows = vec![Row {
            label: "removed volume".into(),
            cells: vec!["125.0 mm³".into(), "45.0 mm³".into()],
        }];
        let sheet = draw(&names, &pictures, &rows).unwrap();
        let layout = Layout::new([200, 150], 2, 1, "removed volume".len());
        let [w, h] = layout.size();
        assert_eq!((sheet.width() as u64, sheet.height() as u64), (w, h));
        let top = layout.margin + layout.title_height;
        for (k, color) in [(0, [255, 0, 0, 255]), (1, [0, 0, 255, 255])] {
            let x = layout.column_x(k);
            assert_eq!(sheet.get_pixel(x + 100, top + 75).0, color);
        }
        // Ink in each column's title band and in each cell of the table.
        let inked = |x0: u32, y0: u32, x1: u32, y1: u32| {
            (y0..y1).any(|y| (x0..x1).any(|x| sheet.get_pixel(x, y)[0] < 120))
        };
        for k in 0..2 {
            let x = layout.column_x(k);
            assert!(inked(x, layout.margin, x + 200, top), "title {k}");
            let y = layout.table_y();
            assert!(inked(x, y, x + 200, y + layout.row_height), "cell {k}");
        }
        assert!(inked(
            layout.margin,
            layout.table_y(),
            layout.column_x(0),
            layout.table_y() + layout.row_height
        ));
    }

    #[test]
    fn a_sheet_too_large_is_refused_before_drawing() {
        let layout = Layout::new([4096, 100], 8, 3, 10);
        assert!(layout.size()[0] > MAX_SIDE as u64);
        let pictures = vec![RgbaImage::new(4096, 1); 5];
        let names = vec![String::new(); 5];
        let e = draw(&names, &pictures, &[]).unwrap_err();
        assert!(format!("{e}").contains("more than 16384"), "{e}");
    }

    #[test]
    fn long_text_is_shortened_to_fit() {
        let painter = TextPainter::new();
        let short = fit(
            &painter,
            Face::Sans,
            14.0,
            "a very long structure name indeed",
            80.0,
        );
        assert!(short.ends_with('…'), "{short}");
        assert!(painter.width(Face::Sans, 14.0, &short) <= 80.0);
    }
}
