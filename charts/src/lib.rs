//! SVG plots for the engineer: transmission-error curves, flank maps (ease-off
//! topography, roll-angle surface), contact paths with contact ellipses and
//! tooth sections.
//!
//! Every function takes plain data (no project types), renders the whole
//! picture into a string with the SVG backend of `plotters` and then writes it
//! atomically ([`formats::output::write_atomic`]): a reader never sees a
//! half-written file.
//!
//! Text is written as SVG `<text>` elements with the generic `sans-serif`
//! family; no font files are needed to produce the plots.
//!
//! The small numerical helpers used by the plots are public and tested on
//! their own: [`nice_ticks`] (1-2-5 tick/contour levels), [`iso_segments`]
//! (marching squares on a structured curvilinear grid) and
//! [`equal_aspect_ranges`] (axis ranges with the same length per pixel in x
//! and y).
//!
//! One module per chart: [`te_curve`] (`curves`), [`flank_map()`]
//! (`flank_map`), [`contact_path()`] (`contact_path`), [`tooth_section`]
//! (`section`), [`outcome_grid()`] (`outcome_grid`), [`pareto_chart`] (`pareto`); the equal-aspect plots share `equal_aspect`, every chart the
//! layout of `frame` and the legend of `legend`; the numerical helpers are
//! in `numeric`.

mod contact_path;
mod curves;
mod equal_aspect;
mod flank_map;
mod frame;
mod legend;
mod numeric;
mod outcome_grid;
mod pareto;
mod section;

pub use contact_path::{contact_path, Ellipse, PathSeries};
pub use curves::{te_curve, Series};
pub use flank_map::{flank_map, FlankMap};
pub use numeric::{equal_aspect_ranges, iso_segments, nice_ticks};
pub use outcome_grid::{outcome_grid, GridCell};
pub use pareto::{pareto_chart, pareto_front, ParetoPoint, ParetoSeries};
pub use section::tooth_section;

use std::path::PathBuf;

/// Error of a plot function. Every message names the output file.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// The input cannot be plotted (no finite data, inconsistent lengths, ...).
    #[error("plot {}: invalid input: {msg}", .path.display())]
    Input { path: PathBuf, msg: String },
    /// The plotting library reported an error while drawing.
    #[error("plot {}: drawing failed: {msg}", .path.display())]
    Drawing { path: PathBuf, msg: String },
    /// Writing the file failed.
    #[error(transparent)]
    Write(#[from] formats::output::WriteError),
}
