//! The whole report from a small fixture in a temporary directory: every
//! markdown table renders as an HTML `<table>`, the report opens with the
//! loaded TE and puts each figure under the section that discusses it, the
//! unloaded TE row is called a calibration where a published value is
//! present, and `results.md` is written and copied between the README's
//! markers (a README without them is left alone).

use std::path::Path;
use validate::report::comparison::{Comparison, Row};
use validate::report::figures::Figure;
use validate::report::gather::ReportFigures;
use validate::report::published::Published;
use validate::report::results;
use validate::studies::utca_check::{Row as UtcaRow, UtcaCheck};

fn utca() -> UtcaCheck {
    UtcaCheck {
        name: "demo".into(),
        side: "drive",
        rows: (0..3)
            .map(|k| UtcaRow {
                pinion_rotation_deg: 1.5 * k as f64,
                fast_te_urad: 30.0 - k as f64,
                direct_te_urad: 30.0 - k as f64,
                difference_urad: 0.0,
            })
            .collect(),
        max_abs_difference_urad: 0.0016,
        fast_te_ptp_urad: 37.77,
        fast_te_mean_urad: 13.44,
        contact_ratio: 2.888,
        fast_ms_per_position: 0.06,
        direct_ms_per_position: 20.9,
        min_gap_um: 9.41e-3,
    }
}

fn row(wheel: &str, torque_nm: f64, mean: f64, reference_mean: f64) -> Row {
    Row {
        pinion_blank: "standard".into(),
        wheel_blank: wheel.into(),
        torque_nm,
        multibody_te_mean_urad: mean,
        multibody_te_ptp_urad: 18.57,
        reference_te_mean_urad: reference_mean,
        reference_te_ptp_urad: 16.07,
        multibody_at_reference_mean_urad: Some(mean),
        multibody_at_reference_ptp_urad: Some(18.57),
        te_mean_difference_pct: (mean - reference_mean) / reference_mean * 100.0,
        te_ptp_difference_pct: 15.5,
        reference_penalty_difference_pct: 0.025,
        reference_max_pressure_mpa: 957.6,
        multibody_steps: 2213,
        multibody_cpu_s_per_step: 7.34e-5,
        multibody_cpu_s: 0.16,
        multibody_table_cpu_s: 1.2,
        reference_positions: 73,
        reference_cpu_s_per_position: 6.1,
        reference_cpu_s: 545.0,
        reference_level: "reference".into(),
        reduced_level_reference_te_mean_urad: None,
        reduced_level_reference_te_ptp_urad: None,
        reduced_level_te_mean_difference_pct: None,
        reduced_level_te_ptp_difference_pct: None,
        published_multibody_te_mean_urad: Some(325.9),
        published_nlfea_te_mean_urad: Some(333.0),
        published_multibody_te_ptp_urad: Some(16.6),
        published_nlfea_te_ptp_urad: Some(17.1),
        published_multibody_cpu_s_per_step: Some(0.8),
        published_nlfea_cpu_s_per_step: Some(1100.0),
        published_multibody_cpu_total_s: Some(240.0),
        published_nlfea_cpu_total_s: Some(77_760.0),
    }
}

/// The comparison's markdown as `comparison::compare` writes it: the
/// run-time table is followed by the breakdown and the contact-pattern
/// paragraphs without a blank line, and the line-load table has escaped
/// bars.
const COMPARISON_MD: &str = "## Loaded TE: reduced model against the reference FE contact (Tables 3 and 4)

Reduced model: the multibody run.

| wheel blank | load, N·m | mean TE reduced, µrad | mean TE reference, µrad | diff % |
|---|---|---|---|---|
| standard | 300 | 359.26 (359.26) | 361.30 | -0.57 |

## Run time (Table 5)

Measured on this machine.

| wheel blank | load, N·m | MB steps |
|---|---|---|
| standard | 300 | 2213 |
### Where the differences come from

Each part of the reduced model measured on its own:

- Meshed flank geometry: 0.022 µrad at most.
- Light load: +0.64 µrad.
Contact pattern standard / standard (pattern_300nm): the reference's pressure peaks at 1890 MPa on the flank's edge at the tip: edge contact.

Note: the reduced model ran with Coulomb friction μ = 0.05; the reference contact is frictionless.


## Mesh convergence of the reference

Three levels.

| level | h |
|---|---|
| reduced | 0.0645 |

## Line load: global FE + Weber–Banaschek against fine-mesh FE

| FE mesh | mean \\|diff\\| % |
|---|---|
| medium | 2.36 |

## Reduced model: run time against error (slices per tooth pair)

| wheel blank | slices |
|---|---|
| standard | 8 |
";

fn svg(tag: &str) -> String {
    format!("<svg width=\"10\" height=\"10\" viewBox=\"0 0 10 10\" xmlns=\"http://www.w3.org/2000/svg\"><!-- {tag} --></svg>")
}

fn figure(file: &str) -> Figure {
    Figure {
        title: format!("Figure {file}"),
        file: file.into(),
        svg: svg(file),
    }
}

/// The flank stage's plots in `flanks`, the loaded figures made up.
fn figures(flanks: &Path, reports: &Path) -> ReportFigures {
    for f in ["te.svg", "contact_path.svg", "ease_off.svg"] {
        std::fs::write(flanks.join(f), svg(f)).unwrap();
    }
    let mut figs = validate::report::gather::report_figures(None, None, flanks, reports);
    assert_eq!(figs.unloaded.len(), 3, "the flank stage's plots are copied");
    assert!(reports.join("unloaded_te.svg").exists());
    figs.loaded_te = vec![
        figure("te_loaded_standard_standard_300nm.svg"),
        figure("te_loaded_standard_lightweight_300nm.svg"),
    ];
    figs.patterns = vec![figure("pattern_standard_standard_300nm.svg")];
    figs.pattern_torque_nm = Some(300.0);
    figs.tradeoff = Some(figure("tradeoff.svg"));
    figs
}

/// Position of `needle` in `hay`, failing with a message when absent.
fn at(hay: &str, needle: &str) -> usize {
    hay.find(needle)
        .unwrap_or_else(|| panic!("'{needle}' not in the report"))
}

#[test]
fn report_from_a_fixture() {
    let tmp = tempfile::tempdir().unwrap();
    let (flanks, reports) = (tmp.path().join("flanks"), tmp.path().join("reports"));
    std::fs::create_dir_all(&flanks).unwrap();
    let figs = figures(&flanks, &reports);
    let c = utca();
    let published = Published {
        value: 37.0,
        source: "white paper Table 3, NLFEA, standard blank".into(),
    };
    let cmp = Comparison {
        rows: vec![
            row("standard", 300.0, 359.26, 361.30),
            row("lightweight", 300.0, 1047.35, 1041.99),
        ],
        markdown: COMPARISON_MD.into(),
    };
    let readme = tmp.path().join("README.md");
    std::fs::write(
        &readme,
        format!(
            "# Toolkit\n\n{}\nold results\n{}\n\nMore.\n",
            results::BEGIN,
            results::END
        ),
    )
    .unwrap();
    let written =
        validate::report::write(&reports, &c, Some(&published), Some(&cmp), &figs, &readme)
            .unwrap();
    let md = std::fs::read_to_string(reports.join("report.md")).unwrap();
    let html = std::fs::read_to_string(reports.join("report.html")).unwrap();

    // Every markdown table is an HTML table, and no table row is text.
    let tables = md.lines().filter(|l| l.starts_with("|---")).count();
    assert_eq!(tables, 7, "{md}");
    assert_eq!(html.matches("<table>").count(), tables, "{html}");
    assert_eq!(html.matches("</table>").count(), tables);
    assert!(!html.contains("<p>|") && !html.contains("<td>---"));
    assert!(html.contains("<th>quantity</th><th>this toolkit</th><th>published</th>"));
    assert!(html.contains("<th>FE mesh</th><th>mean |diff| %</th>"));

    // The loaded TE first, its figures under it, the details after.
    let order = [
        "## Loaded TE",
        "(te_loaded_standard_standard_300nm.svg)",
        "(te_loaded_standard_lightweight_300nm.svg)",
        "### Where the differences come from",
        "Note: the reduced model ran with Coulomb friction",
        "### Contact pattern at 300 N·m",
        "Contact pattern standard / standard (pattern_300nm)",
        "(pattern_standard_standard_300nm.svg)",
        "## Run time (Table 5)",
        "## Reduced model: run time against error",
        "(tradeoff.svg)",
        "| wheel blank | slices |",
        "## Unloaded tooth contact (drive flank)",
        "calibration, not a validation",
        "(unloaded_te.svg)",
        "(contact_path.svg)",
        "(ease_off.svg)",
        "## Surface of roll angles against the direct contact search",
        "## Mesh convergence of the reference",
        "## Line load",
    ];
    for w in order.windows(2) {
        assert!(
            at(&md, w[0]) < at(&md, w[1]),
            "'{}' before '{}'",
            w[0],
            w[1]
        );
    }
    assert!(!md.contains("(SVG in report.html)"), "no figure list");
    // The run-time section holds its own table only.
    let run_time = &md[at(&md, "## Run time")..at(&md, "## Reduced model: run time")];
    assert!(!run_time.contains("Contact pattern") && !run_time.contains("Coulomb"));

    // In the HTML, each SVG inline once, under its section.
    for f in figs.all() {
        assert_eq!(html.matches(&f.svg).count(), 1, "{}", f.file);
    }
    let h = |s: &str| at(&html, s);
    assert!(h("<h2 id=\"loaded-te") < h("<!-- te_loaded_standard_standard_300nm.svg -->"));
    assert!(h("<!-- te_loaded_standard_lightweight_300nm.svg -->") < h("<h3 id=\"where"));
    assert!(h("<h3 id=\"contact-pattern") < h("<!-- pattern_standard_standard_300nm.svg -->"));
    assert!(h("<!-- pattern_standard_standard_300nm.svg -->") < h("<h2 id=\"run-time"));
    assert!(h("<h2 id=\"unloaded") < h("<!-- te.svg -->"));
    assert!(h("<!-- ease_off.svg -->") < h("<h2 id=\"surface-of-roll"));
    assert!(
        html.contains("<div class=\"figures\">"),
        "figures side by side"
    );

    // summary.json: the same keys as before.
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(reports.join("summary.json")).unwrap())
            .unwrap();
    let mut keys: Vec<&String> = summary.as_object().unwrap().keys().collect();
    keys.sort();
    assert_eq!(
        keys,
        [
            "loaded_te",
            "published_te_ptp_1nm_urad",
            "te_ptp_difference_percent",
            "utca"
        ]
    );
    assert_eq!(summary["loaded_te"].as_array().unwrap().len(), 2);

    // results.md: date and commit, one row per blank and load; the README
    // holds the same text between its markers.
    let res = std::fs::read_to_string(reports.join("results.md")).unwrap();
    let first = res.lines().next().unwrap();
    assert!(first.contains(" (UTC) at commit `"), "{first}");
    assert!(
        res.contains("| standard | 300 | 359.26 | 361.30 | -0.56 |"),
        "{res}"
    );
    assert!(
        res.contains("| lightweight | 300 | 1047.35 | 1041.99 | +0.51 |"),
        "{res}"
    );
    // The reduced model's run time holds the contact-element table it runs
    // on: 0.16 s run + 1.2 s table.
    assert!(res.contains("| 1.36 | 545 |"), "{res}");
    assert!(written.readme_updated);
    let new_readme = std::fs::read_to_string(&readme).unwrap();
    assert!(!new_readme.contains("old results"));
    assert!(new_readme.starts_with(&format!("# Toolkit\n\n{}\n\n", results::BEGIN)));
    assert!(new_readme.contains(res.trim_end()));
    assert!(new_readme.ends_with(&format!("{}\n\nMore.\n", results::END)));
}

#[test]
fn without_published_value_or_loaded_comparison() {
    let tmp = tempfile::tempdir().unwrap();
    let (flanks, reports) = (tmp.path().join("flanks"), tmp.path().join("reports"));
    std::fs::create_dir_all(&flanks).unwrap();
    let figs = validate::report::gather::report_figures(None, None, &flanks, &reports);
    assert!(figs.all().next().is_none(), "no plots, no figures");
    let readme = tmp.path().join("README.md");
    let text = format!("# Toolkit\n\n{}\nkept\n{}\n", results::BEGIN, results::END);
    std::fs::write(&readme, &text).unwrap();
    let written = validate::report::write(&reports, &utca(), None, None, &figs, &readme).unwrap();
    let md = std::fs::read_to_string(reports.join("report.md")).unwrap();
    let html = std::fs::read_to_string(reports.join("report.html")).unwrap();
    assert!(
        !md.contains("calibration"),
        "no published value, no calibration note"
    );
    assert!(md.contains("not available"));
    assert!(at(&md, "## Loaded TCA") < at(&md, "## Unloaded tooth contact"));
    assert_eq!(html.matches("<table>").count(), 2);
    // No loaded results: the README keeps what it has.
    assert!(!written.readme_updated);
    assert_eq!(std::fs::read_to_string(&readme).unwrap(), text);
    assert!(std::fs::read_to_string(reports.join("results.md"))
        .unwrap()
        .contains("No loaded comparison"));
}

#[test]
fn readme_without_markers_is_left_alone() {
    let tmp = tempfile::tempdir().unwrap();
    let (flanks, reports) = (tmp.path().join("flanks"), tmp.path().join("reports"));
    std::fs::create_dir_all(&flanks).unwrap();
    let figs = validate::report::gather::report_figures(None, None, &flanks, &reports);
    let cmp = Comparison {
        rows: vec![row("standard", 300.0, 359.26, 361.30)],
        markdown: COMPARISON_MD.into(),
    };
    let readme = tmp.path().join("README.md");
    std::fs::write(&readme, "# Toolkit\n\nNo markers.\n").unwrap();
    let written =
        validate::report::write(&reports, &utca(), None, Some(&cmp), &figs, &readme).unwrap();
    assert!(!written.readme_updated);
    assert_eq!(
        std::fs::read_to_string(&readme).unwrap(),
        "# Toolkit\n\nNo markers.\n"
    );
    assert!(reports.join("results.md").exists());
}

#[test]
fn utca_check_is_one_set_listing_its_checksum_and_the_scene_and_design() {
    let tmp = tempfile::tempdir().unwrap();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../reference");
    let scene = root.join("scenes/small.toml");
    let design = root.join("white_paper_20x43.toml");
    let out = tmp.path().join("utca");
    validate::studies::utca_check::write_set(&utca(), &scene, &design, &out).unwrap();
    let info = formats::result_set::verify_files(&out).unwrap().unwrap();
    assert!(
        info.files.contains_key("utca_check.json"),
        "{:?}",
        info.files
    );
    assert!(info.inputs.contains_key("scene") && info.inputs.contains_key("design"));
    // A result edited after the run is detected.
    let p = out.join("utca_check.json");
    let text = std::fs::read_to_string(&p).unwrap();
    std::fs::write(&p, text.replacen("37.77", "37.78", 1)).unwrap();
    let err = formats::result_set::verify_files(&out).unwrap_err();
    assert!(err.to_string().contains("changed since run"), "{err}");
    // A missing input is named.
    let err = validate::studies::utca_check::write_set(
        &utca(),
        &tmp.path().join("none.toml"),
        &design,
        &out,
    )
    .unwrap_err();
    assert!(err.to_string().contains("none.toml"), "{err}");
}
