//! The small scene's text (`reference/scenes/small.toml`) with its design
//! path made absolute, for the tests that write variants of it into
//! scratch folders.

use std::path::{Path, PathBuf};

/// The project's `reference/` folder.
pub fn reference() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../reference")
}

/// The small scene's text, its design path absolute.
pub fn small_scene_text() -> String {
    std::fs::read_to_string(reference().join("scenes/small.toml"))
        .unwrap()
        .replace(
            "design = \"../white_paper_20x43.toml\"",
            &format!("design = {:?}", reference().join("white_paper_20x43.toml")),
        )
}
