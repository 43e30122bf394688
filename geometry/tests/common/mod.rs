#![allow(dead_code)]
//! Shared helpers of the integration tests.

use geometry::design::{DesignFile, PairData};
use geometry::design_file::load_pair;
use geometry::pair::PairGeometry;
use std::path::PathBuf;

pub fn reference(name: &str) -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../reference")).join(name)
}

pub fn white_paper_path() -> PathBuf {
    reference("white_paper_20x43.toml")
}

/// The white-paper pair as designed (with its ease-off).
pub fn white_paper() -> PairData {
    load_pair(&white_paper_path()).expect("white-paper design loads")
}

/// The white-paper pair without any flank modification (conjugate).
pub fn white_paper_conjugate() -> PairData {
    let mut p = white_paper();
    p.ease_off = Default::default();
    p
}

pub fn geometry(p: &PairData) -> PairGeometry {
    PairGeometry::new(p).expect("pair geometry")
}

/// The white-paper design file parsed, for tests that alter fields.
pub fn white_paper_file() -> DesignFile {
    DesignFile::load(&white_paper_path()).unwrap()
}

/// The tabulated surface of roll angles on a coarse 21 × 21 grid, for tests
/// that search contact directly.
pub fn coarse_roll_surface(fp: &geometry::pair::FlankPair) -> geometry::utca::RollSurface {
    geometry::utca::RollSurface::new(
        fp,
        geometry::utca::LineGrid {
            n_face: 21,
            n_profile: 21,
        },
    )
    .expect("roll surface")
}
