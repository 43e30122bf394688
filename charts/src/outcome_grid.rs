//! A grid of labelled cells coloured by class ([`outcome_grid`]): one row
//! per case group, one cell per case, e.g. a stress matrix coloured by
//! outcome.

use crate::PlotError;
use formats::output::write_atomic;
use plotters::prelude::*;
use std::path::Path;

/// One cell: its row and column, its class (index into the classes'
/// names and colours) and the text written in it.
#[derive(Debug, Clone)]
pub struct GridCell {
    pub row: usize,
    pub col: usize,
    pub class: usize,
    pub text: String,
}

/// Fill colours of the classes, in order (green, amber, red, grey, ...).
const CLASS_COLOURS: [RGBColor; 5] = [
    RGBColor(120, 190, 120),
    RGBColor(240, 190, 90),
    RGBColor(220, 90, 80),
    RGBColor(190, 190, 190),
    RGBColor(130, 160, 220),
];

const CELL_W: u32 = 96;
const CELL_H: u32 = 26;
const LABEL_W: u32 = 250;
const TOP: u32 = 56;

/// Draws the grid: `rows` their labels (left), `classes` the legend names
/// of the classes (at most five), every cell in its class's colour with its
/// text. Errors: [`PlotError::Input`] for a cell outside the rows, a class
/// without a name, or more classes than colours.
pub fn outcome_grid(
    path: &Path,
    title: &str,
    rows: &[String],
    classes: &[&str],
    cells: &[GridCell],
) -> Result<(), PlotError> {
    let input = |msg: String| PlotError::Input {
        path: path.to_path_buf(),
        msg,
    };
    if classes.len() > CLASS_COLOURS.len() {
        return Err(input(format!(
            "{} classes, at most {}",
            classes.len(),
            CLASS_COLOURS.len()
        )));
    }
    if let Some(c) = cells
        .iter()
        .find(|c| c.row >= rows.len() || c.class >= classes.len())
    {
        return Err(input(format!(
            "cell at row {} (of {}) with class {} (of {})",
            c.row,
            rows.len(),
            c.class,
            classes.len()
        )));
    }
    let cols = cells.iter().map(|c| c.col + 1).max().unwrap_or(0) as u32;
    let w = LABEL_W + cols.max(6) * CELL_W + 20;
    let h = TOP + rows.len() as u32 * CELL_H + 50;
    let drawing = |msg: String| PlotError::Drawing {
        path: path.to_path_buf(),
        msg,
    };
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| drawing(e.to_string()))?;
        let font = ("sans-serif", 13).into_font();
        let small = ("sans-serif", 11).into_font();
        root.draw(&Text::new(
            title.to_string(),
            (10, 10),
            ("sans-serif", 16).into_font(),
        ))
        .map_err(|e| drawing(e.to_string()))?;
        // Legend.
        for (k, name) in classes.iter().enumerate() {
            let x = 10 + k as i32 * 150;
            root.draw(&Rectangle::new(
                [(x, 32), (x + 14, 46)],
                CLASS_COLOURS[k].filled(),
            ))
            .map_err(|e| drawing(e.to_string()))?;
            root.draw(&Text::new(name.to_string(), (x + 20, 33), font.clone()))
                .map_err(|e| drawing(e.to_string()))?;
        }
        for (r, label) in rows.iter().enumerate() {
            let y = (TOP + r as u32 * CELL_H) as i32;
            root.draw(&Text::new(label.clone(), (10, y + 7), font.clone()))
                .map_err(|e| drawing(e.to_string()))?;
        }
        for c in cells {
            let x = (LABEL_W + c.col as u32 * CELL_W) as i32;
            let y = (TOP + c.row as u32 * CELL_H) as i32;
            let (x1, y1) = (x + CELL_W as i32 - 2, y + CELL_H as i32 - 2);
            root.draw(&Rectangle::new(
                [(x, y), (x1, y1)],
                CLASS_COLOURS[c.class].filled(),
            ))
            .map_err(|e| drawing(e.to_string()))?;
            root.draw(&Text::new(c.text.clone(), (x + 4, y + 7), small.clone()))
                .map_err(|e| drawing(e.to_string()))?;
        }
        root.present().map_err(|e| drawing(e.to_string()))?;
    }
    write_atomic(path, svg.as_bytes())?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outcome_grid_writes_every_cell_and_refuses_a_cell_outside_the_rows() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("g.svg");
        let rows = vec!["a · load".to_string(), "b · slices".to_string()];
        let cells = vec![
            GridCell {
                row: 0,
                col: 0,
                class: 0,
                text: "0 N·m".into(),
            },
            GridCell {
                row: 1,
                col: 3,
                class: 2,
                text: "160".into(),
            },
        ];
        outcome_grid(&p, "t", &rows, &["converged", "refused", "failed"], &cells).unwrap();
        let s = std::fs::read_to_string(&p).unwrap();
        assert!(s.contains("0 N·m") && s.contains("160") && s.contains("b · slices"));
        let bad = [GridCell {
            row: 2,
            col: 0,
            class: 0,
            text: String::new(),
        }];
        assert!(outcome_grid(&p, "t", &rows, &["converged"], &bad).is_err());
    }
}
