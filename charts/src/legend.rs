//! The framed legend in the right-hand column of a chart.

use crate::frame::{de, fit_text, text_style, text_width, Area, DResult};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

/// How a legend entry is drawn.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Sample {
    Line {
        color: RGBColor,
        width: u32,
        dashed: bool,
    },
    LineMarker(RGBColor),
    Patch(RGBColor),
}

const LEGEND_FONT: f64 = 18.0;
const LEGEND_ROW: i32 = 26;

/// Width of a legend column for these names.
pub(crate) fn legend_width(names: &[&str]) -> u32 {
    let longest = names
        .iter()
        .map(|s| text_width(s, LEGEND_FONT))
        .max()
        .unwrap_or(0);
    (longest + 66).clamp(120, 380) as u32
}

/// Framed legend at vertical pixel offset `top` of `area`.
pub(crate) fn draw_legend(area: &Area<'_>, top: i32, entries: &[(String, Sample)]) -> DResult {
    if entries.is_empty() {
        return Ok(());
    }
    let (w, h) = area.dim_in_pixel();
    let fit = (((h as i32 - top - 12) / LEGEND_ROW).max(1)) as usize;
    let (shown, more) = if entries.len() > fit {
        (fit.saturating_sub(1), entries.len() - fit.saturating_sub(1))
    } else {
        (entries.len(), 0)
    };
    let rows = shown + usize::from(more > 0);
    let (x0, x1) = (4, w as i32 - 8);
    let y1 = top + rows as i32 * LEGEND_ROW + 10;
    area.draw(&Rectangle::new([(x0, top), (x1, y1)], WHITE.filled()))
        .map_err(de)?;
    area.draw(&Rectangle::new(
        [(x0, top), (x1, y1)],
        RGBColor(160, 160, 160).stroke_width(1),
    ))
    .map_err(de)?;
    let style = text_style(LEGEND_FONT, HPos::Left, VPos::Center);
    for (j, (name, sample)) in entries.iter().take(shown).enumerate() {
        let y = top + 5 + j as i32 * LEGEND_ROW + LEGEND_ROW / 2;
        let (sx0, sx1) = (x0 + 8, x0 + 40);
        match *sample {
            Sample::Line {
                color,
                width,
                dashed,
            } => {
                let st = color.stroke_width(width);
                if dashed {
                    for s in [0, 12, 24] {
                        area.draw(&PathElement::new(vec![(sx0 + s, y), (sx0 + s + 7, y)], st))
                            .map_err(de)?;
                    }
                } else {
                    area.draw(&PathElement::new(vec![(sx0, y), (sx1, y)], st))
                        .map_err(de)?;
                }
            }
            Sample::LineMarker(color) => {
                area.draw(&PathElement::new(
                    vec![(sx0, y), (sx1, y)],
                    color.stroke_width(2),
                ))
                .map_err(de)?;
                area.draw(&Circle::new(((sx0 + sx1) / 2, y), 3, color.filled()))
                    .map_err(de)?;
            }
            Sample::Patch(color) => {
                area.draw(&Rectangle::new(
                    [(sx0, y - 6), (sx1, y + 6)],
                    color.mix(0.3).filled(),
                ))
                .map_err(de)?;
                area.draw(&Rectangle::new(
                    [(sx0, y - 6), (sx1, y + 6)],
                    color.stroke_width(1),
                ))
                .map_err(de)?;
            }
        }
        let shown_name = fit_text(name, x1 - (sx1 + 8) - 4, LEGEND_FONT);
        area.draw(&Text::new(shown_name, (sx1 + 8, y), style.clone()))
            .map_err(de)?;
    }
    if more > 0 {
        let y = top + 5 + shown as i32 * LEGEND_ROW + LEGEND_ROW / 2;
        area.draw(&Text::new(
            format!("\u{2026} {more} more"),
            (x0 + 8, y),
            style.clone(),
        ))
        .map_err(de)?;
    }
    Ok(())
}
