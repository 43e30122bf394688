//! The reference stage's options of the tests (the CLI's defaults: penalty
//! factor 100, check 200, 2 µm start band, 60 µm search gap; reduced level,
//! 96 right-hand sides per block), at `stride` and, for shard runs, `shard`.

use validate::reference::reference_ltca::ReferenceSettings;
use validate::reference::reference_options::StageOptions;

pub fn options(stride: usize, shard: Option<(usize, usize)>) -> StageOptions {
    StageOptions {
        level: "reduced".into(),
        settings: ReferenceSettings {
            penalty_factor: 100.0,
            penalty_factor_check: 200.0,
            start_band_m: 2e-6,
            search_gap_m: 60e-6,
            passes: Default::default(),
        },
        stride,
        stride_lightweight: None,
        block: 96,
        compare_cache: false,
        shard,
        memory_bytes: None,
    }
}
