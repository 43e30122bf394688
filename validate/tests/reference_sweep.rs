//! The reference sweep's bookkeeping on the small scene's coarse (6 × 10)
//! meshes: a sweep split into shards and collected equals the single run,
//! `--compare-cache` accepts the cache it wrote, and refuses one whose
//! value was changed.

use geometry::scene::Scene;
#[path = "support/shared_meshes.rs"]
mod shared_meshes;
use std::path::Path;
use validate::reference::reference_ltca::PositionResult;
use validate::reference::reference_options::StageOptions;
use validate::reference::reference_stage::{reference_dir, run, CacheComparison};
#[path = "support/reference_options.rs"]
mod reference_options;

fn options() -> StageOptions {
    reference_options::options(2, None)
}

/// TE columns of `te.csv` (every value after the header).
fn te_values(out: &Path) -> Vec<f64> {
    let text = std::fs::read_to_string(
        reference_dir(out, "small", "reduced").join("standard_standard/te.csv"),
    )
    .unwrap();
    text.lines()
        .skip(1)
        .flat_map(|l| {
            l.split(',')
                .map(|v| v.parse::<f64>().unwrap())
                .collect::<Vec<_>>()
        })
        .collect()
}

#[test]
fn shards_collect_into_the_single_run_and_compare_cache_catches_a_changed_value() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let scene = Scene::load(&root.join("reference/scenes/small.toml")).unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let meshes = shared_meshes::reduced_meshes(&scene);

    // One run over the whole sweep. What other commands keep in the
    // folder (a study's results, another blank pair's) survives it.
    let single = tmp.path().join("single");
    let folder = reference_dir(&single, &scene.scene.name, "reduced");
    std::fs::create_dir_all(folder.join("other_blanks")).unwrap();
    std::fs::write(folder.join("convergence.json"), "{\"study\": 1}").unwrap();
    std::fs::write(folder.join("other_blanks/summary.json"), "{}").unwrap();
    let a = run(&scene, &meshes, &single, &options()).unwrap();
    assert_eq!(
        std::fs::read_to_string(folder.join("convergence.json")).unwrap(),
        "{\"study\": 1}"
    );
    assert!(folder.join("other_blanks/summary.json").exists());
    // The set records the design and both meshes it read.
    let stamp = formats::result_set::read_run_info(&folder)
        .unwrap()
        .expect("run.json");
    for key in [
        "design",
        "mesh:pinion_standard_reduced",
        "mesh:wheel_standard_reduced",
    ] {
        assert!(
            stamp.inputs.contains_key(key),
            "{key} not in {:?}",
            stamp.inputs
        );
    }
    let n = a[0].positions;
    assert!(n >= 8, "{n} positions");

    // Three shards, then a collecting run that solves nothing.
    let sharded = tmp.path().join("sharded");
    for k in 0..3 {
        let opt = StageOptions {
            shard: Some((k, 3)),
            ..options()
        };
        assert!(run(&scene, &meshes, &sharded, &opt).unwrap().is_empty());
    }
    let b = run(&scene, &meshes, &sharded, &options()).unwrap();
    assert_eq!(b[0].positions_reused, n, "every position from the shards");
    let (ta, tb) = (te_values(&single), te_values(&sharded));
    assert_eq!(ta.len(), tb.len());
    let scale = ta.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    for (x, y) in ta.iter().zip(&tb) {
        assert!((x - y).abs() <= 1e-12 * scale, "{x} vs {y}");
    }

    // The cache compared with positions solved anew.
    let compare = StageOptions {
        compare_cache: true,
        ..options()
    };
    run(&scene, &meshes, &single, &compare).unwrap();
    let odir = reference_dir(&single, "small", "reduced").join("standard_standard");
    let c: CacheComparison =
        serde_json::from_str(&std::fs::read_to_string(odir.join("compare_cache.json")).unwrap())
            .unwrap();
    assert_eq!(c.positions_compared, n);
    assert!(c.worst() < 1e-12, "{c:?}");
    // Added in place to the committed set, recorded with its checksum and
    // the set's run id.
    let added = "standard_standard/compare_cache.json";
    let reg = formats::added_files::registry(&folder).unwrap();
    assert!(reg[added].stamp.of_run_id.is_some());
    assert!(matches!(
        formats::added_files::read_added(&folder, added).unwrap(),
        formats::added_files::AddedState::Current(_)
    ));

    // One cached TE changed by 1e-5: refused.
    let cached = std::fs::read_dir(odir.join("positions"))
        .unwrap()
        .flat_map(|d| std::fs::read_dir(d.unwrap().path()).unwrap())
        .map(|f| f.unwrap().path())
        .find(|p| p.file_name().unwrap().to_string_lossy().starts_with("phi_"))
        .unwrap();
    let mut r: PositionResult =
        serde_json::from_str(&std::fs::read_to_string(&cached).unwrap()).unwrap();
    r.loads[0].te *= 1.0 + 1e-5;
    std::fs::write(&cached, serde_json::to_string(&r).unwrap()).unwrap();
    let err = run(&scene, &meshes, &single, &compare).unwrap_err();
    assert!(err.to_string().contains("differ from the cache"), "{err}");

    // A mesh changed after the mesh stage wrote it is refused before work.
    let copied = tmp.path().join("meshes");
    std::fs::create_dir_all(copied.join("small")).unwrap();
    for f in std::fs::read_dir(meshes.join("small")).unwrap().flatten() {
        if f.path().is_file() {
            std::fs::copy(f.path(), copied.join("small").join(f.file_name())).unwrap();
        }
    }
    let msh = copied.join("small/pinion_standard_reduced.msh");
    let mut bytes = std::fs::read(&msh).unwrap();
    bytes.extend_from_slice(b"\n");
    std::fs::write(&msh, bytes).unwrap();
    let err = run(&scene, &copied, &tmp.path().join("changed"), &options()).unwrap_err();
    assert!(
        format!("{err:#}").contains("changed since the mesh stage wrote it"),
        "{err:#}"
    );

    // Factors that cannot fit in the memory allowed are refused before
    // any factoring, with the estimate (positions not cached: a new output).
    let tight = StageOptions {
        memory_bytes: Some(1_000_000),
        ..options()
    };
    let err = run(&scene, &meshes, &tmp.path().join("tight"), &tight).unwrap_err();
    let msg = format!("{err:#}");
    assert!(
        msg.contains("would hold Cholesky factors")
            && msg.contains("pinion:")
            && msg.contains("0.0 GB are available"),
        "{msg}"
    );

    // A new run replaces the set: the old comparison no longer belongs to it.
    run(&scene, &meshes, &single, &options()).unwrap();
    let state = formats::added_files::read_added(&folder, added).unwrap();
    assert!(
        matches!(state, formats::added_files::AddedState::OtherSet { .. }),
        "{state:?}"
    );
}
