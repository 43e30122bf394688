//! The report's section "Flexible gearbox (multibody)": `solver dynamic`
//! on `reference/scenes/white_paper_gearbox.toml` (the white-paper pair on
//! the compliant bearings of `white_paper_bearings.toml` with both shafts
//! as Timoshenko beam elements with mass, `solver::gearbox`).
//!
//! Reads `<out>/white_paper_gearbox/multibody/summary.json`: per blank pair
//! the structure (coordinates, shaft masses), the FE housing where there is
//! one (its mesh, its modes against the whole FE housing's with the verdict
//! against 1 %, the seats' largest accelerations, the spectrogram of a
//! seat's acceleration), the loaded modes with the
//! share of their kinetic energy per part, where the excitation orders
//! meet them within the run-up's speeds, the run-up on the gearbox beside
//! the compliant-bearing run-up on the statically condensed shafts (TE,
//! bearing forces, CPU per step, both from the same summary), the gearbox
//! run-up's spectrogram with the modes drawn, and both run-ups' wheel
//! bearing-force amplitudes at the marked orders from their order analyses
//! (`gearbox_runup_orders.json`, `bearings_runup_orders.json`) with the
//! lightweight over the standard wheel at the hole order and the side
//! bands. An absent summary is one line of text. Every number is formatted
//! from the files.

use super::lightweight_revolution::{at, cells, nearest_window, side_bands, SHOWN};
use crate::report::figures::{copied, Figure};
use formats::summaries::{CompliantRunSummary, DynamicSummary, GearboxSummary, RunupOrders};
use std::fmt::Write as _;
use std::path::Path;

/// The scene whose runs the section reports.
pub const GEARBOX_SCENE: &str = "white_paper_gearbox";

/// The section's markdown and figures (written into the report directory).
#[derive(Debug, Clone, Default)]
pub struct GearboxSection {
    pub markdown: String,
    pub figures: Vec<Figure>,
}

fn blank_name(d: &DynamicSummary) -> String {
    format!("{:?}_{:?}", d.pinion_blank, d.wheel_blank).to_lowercase()
}

/// The section from the stages' output root `out`, its figures copied into
/// `reports`.
pub fn section(out: Option<&Path>, reports: &Path) -> GearboxSection {
    let mut s = String::from("## Flexible gearbox (multibody)\n\n");
    let absent = |mut s: String, why: String| {
        let _ = writeln!(s, "No flexible-gearbox runs: {why}.\n");
        GearboxSection {
            markdown: s,
            figures: vec![],
        }
    };
    let Some(out) = out else {
        return absent(s, "the report was built without an output root".into());
    };
    let path = out
        .join(GEARBOX_SCENE)
        .join("multibody")
        .join("summary.json");
    let dynamic: Vec<DynamicSummary> = match std::fs::read_to_string(&path)
        .map_err(|e| e.to_string())
        .and_then(|t| serde_json::from_str(&t).map_err(|e| e.to_string()))
    {
        Ok(v) => v,
        Err(e) => {
            return absent(
                s,
                format!(
                    "`{}` cannot be read ({e}); `solver dynamic reference/scenes/{GEARBOX_SCENE}.toml` writes it",
                    path.display()
                ),
            )
        }
    };
    let housing = if dynamic.iter().any(|d| {
        d.compliant
            .as_ref()
            .and_then(|c| c.gearbox.as_ref())
            .is_some_and(|g| g.housing.is_some())
    }) {
        "an FE housing reduced onto the bearing seats (below)"
    } else {
        "a rigid housing"
    };
    let _ = writeln!(
        s,
        "`solver dynamic` on `reference/scenes/{GEARBOX_SCENE}.toml`: the white-paper pair on compliant bearings, each shaft from its gear's seat to its far bearing as Timoshenko beam elements with their mass (consistent mass, `solver::bearings::timoshenko`), the gears rigid on their seats, the bearings on {housing}. The modes are those of the gearbox loaded at the run-up's torque, the contact element linearized at the quasi-static start; each mode's kinetic energy is split by what moves. The compliant-bearing run-up beside it is the same scene's, the shafts statically condensed onto the seats (massless).\n"
    );
    let mut figures = Vec::new();
    let mut any = false;
    // Per blank pair: (wheel blank, gearbox orders, compliant orders).
    let mut orders: Vec<(String, Option<RunupOrders>, Option<RunupOrders>)> = Vec::new();
    for d in &dynamic {
        let Some(c) = &d.compliant else { continue };
        let Some(g) = &c.gearbox else { continue };
        any = true;
        let b = blank_name(d);
        let _ = writeln!(s, "### {b}\n");
        structure_line(&mut s, g);
        housing_lines(&mut s, g);
        modes_table(&mut s, g);
        crossings_table(&mut s, g);
        let compliant = c.runs.iter().find(|r| r.case == "run-up");
        runs_table(&mut s, g.run.as_ref(), compliant);
        let dir = out.join(GEARBOX_SCENE).join("multibody").join(&b);
        let read = |f: &str| -> Option<RunupOrders> {
            serde_json::from_str(&std::fs::read_to_string(dir.join(f)).ok()?).ok()
        };
        orders.push((
            format!("{:?}", d.wheel_blank).to_lowercase(),
            read("gearbox_runup_orders.json"),
            read("bearings_runup_orders.json"),
        ));
        if let Some(f) = copied(
            &format!("Wheel bearings' force, flexible gearbox ({b}), run-up"),
            &dir.join("gearbox_runup_spectrogram.svg"),
            reports,
            &format!("gearbox_{b}_runup_spectrogram.svg"),
        ) {
            let _ = writeln!(
                s,
                "Run-up spectrogram of the wheel bearings' total force on the flexible gearbox, {b}: the order lines and the modes above (dashed); where an order line crosses a dashed line, that order meets that mode.\n"
            );
            crate::report::figures::figure_lines(&mut s, std::slice::from_ref(&f), false);
            figures.push(f);
        }
        if let Some(f) = copied(
            &format!("Housing acceleration at the wheel's first seat ({b}), run-up"),
            &dir.join("gearbox_runup_housing_spectrogram.svg"),
            reports,
            &format!("gearbox_{b}_runup_housing_spectrogram.svg"),
        ) {
            let _ = writeln!(
                s,
                "Run-up spectrogram of the housing's acceleration |a| at the seat of the wheel's first bearing, {b}, with the same order lines and modes.\n"
            );
            crate::report::figures::figure_lines(&mut s, std::slice::from_ref(&f), false);
            figures.push(f);
        }
    }
    if !any {
        s.push_str("The multibody summary has no flexible-gearbox runs (the scene has no `[bearings.gearbox]`).\n\n");
    }
    orders_table(&mut s, &orders, &[500.0, 750.0, 1000.0]);
    GearboxSection {
        markdown: s,
        figures,
    }
}

fn structure_line(s: &mut String, g: &GearboxSummary) {
    let _ = writeln!(
        s,
        "{} coordinates; shafts {:.3} kg (pinion) and {:.3} kg (wheel), elements of at most {} mm; modes up to the scene's limit: {}, linearized at {} N·m. Left out: {}.\n",
        g.coordinates,
        g.shaft_mass_kg[0],
        g.shaft_mass_kg[1],
        g.shaft_element_mm,
        g.modes.len(),
        g.modes_torque_nm,
        g.notes.join("; ")
    );
}

/// The bound the housing's reduction is held to: its modes within 1 % of
/// the whole FE housing's over the gearbox's range.
pub const HOUSING_TRUNCATION_LIMIT: f64 = 0.01;

/// The FE housing: what it is, its modes against the whole FE housing's
/// with the verdict, and the seats' largest accelerations.
pub fn housing_lines(s: &mut String, g: &GearboxSummary) {
    let Some(h) = &g.housing else {
        return;
    };
    let _ = writeln!(
        s,
        "Housing: tet10 FE body meshed by gmsh ({} nodes, {} elements, {:.1} kg): a wall per bearing on a floor clamped at its four feet, at least {:.1} mm from the gears' blanks and the shafts; reduced by Craig–Bampton onto its {} bearing seats (each bore rigid with its bearing's centre) and {} fixed-interface modes up to {:.0} Hz (cut-off {:.0} Hz). Its modes alone (feet clamped, seats free) against the whole FE housing's, no truncation:\n",
        h.nodes,
        h.elements,
        h.mass_kg,
        h.least_gap_mm,
        h.seats.len(),
        h.fixed_interface_modes,
        h.highest_fixed_interface_hz,
        h.modes_up_to_hz
    );
    s.push_str("| mode | reduced (Hz) | whole FE (Hz) | difference (%) |\n|---:|---:|---:|---:|\n");
    for (i, (r, w)) in h.reduced_hz.iter().zip(&h.reference_hz).enumerate() {
        let _ = writeln!(
            s,
            "| {i} | {r:.1} | {w:.1} | {:+.2} |",
            100.0 * (r / w - 1.0)
        );
    }
    let top = h.reference_hz.last().copied().unwrap_or(0.0);
    let verdict = if h.truncation_error <= HOUSING_TRUNCATION_LIMIT {
        format!(
            "within the {:.0} % the reduction is held to",
            100.0 * HOUSING_TRUNCATION_LIMIT
        )
    } else {
        format!(
            "above the {:.0} % the reduction is held to: keep fixed-interface modes to a higher `modes_up_to_hz`",
            100.0 * HOUSING_TRUNCATION_LIMIT
        )
    };
    let _ = writeln!(
        s,
        "\nLargest difference up to {top:.0} Hz: {:.2} %, {verdict}.\n",
        100.0 * h.truncation_error
    );
    if !h.seat_acceleration_m_s2.is_empty() {
        let seats: Vec<String> = h
            .seats
            .iter()
            .zip(&h.seat_acceleration_m_s2)
            .map(|(&(m, i), a)| format!("{} bearing {i} {a:.1}", ["pinion", "wheel"][m]))
            .collect();
        let _ = writeln!(
            s,
            "Largest acceleration of each seat during the run-up (m/s²): {}.\n",
            seats.join(", ")
        );
    }
}

/// The modes with their kinetic energy by part, in %.
pub fn modes_table(s: &mut String, g: &GearboxSummary) {
    if g.modes.is_empty() {
        s.push_str("No mode below the scene's `modes_up_to_hz`.\n\n");
        return;
    }
    // Only the parts some mode moves.
    let used: Vec<usize> = (0..g.energy_parts.len())
        .filter(|&p| {
            g.modes
                .iter()
                .any(|m| m.energy_share.get(p).is_some_and(|e| *e >= 0.005))
        })
        .collect();
    s.push_str("| mode | frequency (Hz) |");
    for &p in &used {
        let _ = write!(s, " {} (%) |", g.energy_parts[p]);
    }
    s.push_str("\n|---:|---:|");
    s.push_str(&"---:|".repeat(used.len()));
    s.push('\n');
    for (i, m) in g.modes.iter().enumerate() {
        let _ = write!(s, "| {i} | {:.1} |", m.frequency_hz);
        for &p in &used {
            let _ = write!(
                s,
                " {:.1} |",
                100.0 * m.energy_share.get(p).copied().unwrap_or(0.0)
            );
        }
        s.push('\n');
    }
    s.push('\n');
}

/// Where the orders meet the modes.
pub fn crossings_table(s: &mut String, g: &GearboxSummary) {
    if g.crossings.is_empty() {
        s.push_str("No excitation order meets a listed mode within the run-up's speeds.\n\n");
        return;
    }
    s.push_str("| pinion speed (rpm) | order | mode | frequency (Hz) |\n|---:|---:|---:|---:|\n");
    for c in &g.crossings {
        let _ = writeln!(
            s,
            "| {:.0} | {:.2} | {} | {:.1} |",
            c.pinion_rpm, c.order, c.mode, c.frequency_hz
        );
    }
    s.push('\n');
}

/// Wheel bearing-force amplitudes at the marked orders, from the run-ups'
/// order analyses (the window of one wheel revolution whose mean speed is
/// nearest each of `speeds`), gearbox and compliant bearings per wheel
/// blank, and the lightweight over the standard wheel at the hole order and
/// the side bands for each model.
pub fn orders_table(
    s: &mut String,
    orders: &[(String, Option<RunupOrders>, Option<RunupOrders>)],
    speeds: &[f64],
) {
    let has_windows = |o: &Option<RunupOrders>| o.as_ref().is_some_and(|o| !o.windows.is_empty());
    if !orders
        .iter()
        .any(|(_, g, c)| has_windows(g) || has_windows(c))
    {
        s.push_str("No run-up order analysis with a whole wheel revolution (the run-ups are shorter than one).\n\n");
        return;
    }
    let _ = writeln!(
        s,
        "Wheel bearings' total force at the marked pinion orders (N), the run-ups' window of one wheel revolution nearest each speed:\n\n| pinion rpm | wheel | model | window rpm | {} |\n|---:|---|---|---:|{}",
        SHOWN.join(" | "),
        "---:|".repeat(SHOWN.len())
    );
    let mut ratios = Vec::new();
    for &rpm in speeds {
        // (hole order, side bands together) per model and wheel blank.
        let mut side: [[Option<[f64; 2]>; 2]; 2] = [[None; 2]; 2];
        for (wheel, g, c) in orders {
            for (k, (name, o)) in [("flexible gearbox", g), ("compliant, condensed shafts", c)]
                .into_iter()
                .enumerate()
            {
                let Some(w) = o.as_ref().and_then(|o| nearest_window(o, rpm)) else {
                    continue;
                };
                let _ = writeln!(
                    s,
                    "| {rpm:.0} | {wheel} | {name} | {:.0} | {} |",
                    w.mean_pinion_rpm,
                    cells(&w.marked)
                );
                let sb = side_bands(&w.marked);
                let hole = at(&w.marked, "3·20/43").unwrap_or(0.0);
                side[k][usize::from(wheel == "lightweight")] = Some([hole, sb]);
            }
        }
        for (k, name) in ["flexible gearbox", "compliant bearings"]
            .iter()
            .enumerate()
        {
            if let [Some(std), Some(light)] = side[k] {
                ratios.push(format!(
                    "{name} at {rpm:.0} rpm: {:.1} and {:.1}",
                    light[0] / std[0].max(1e-300),
                    light[1] / std[1].max(1e-300)
                ));
            }
        }
    }
    s.push('\n');
    if !ratios.is_empty() {
        let _ = writeln!(
            s,
            "Lightweight over standard wheel, at the hole order 3·20/43 and at the side bands 20 ± 1.40 (sum of both): {}. Where the second is near 1, the side bands do not stand above the windows' floor.\n",
            ratios.join("; ")
        );
    }
}

/// The gearbox run-up beside the compliant-bearing one.
pub fn runs_table(
    s: &mut String,
    gearbox: Option<&CompliantRunSummary>,
    compliant: Option<&CompliantRunSummary>,
) {
    let Some(g) = gearbox else {
        s.push_str("No run-up on the gearbox (the scene runs none for this blank pair).\n\n");
        return;
    };
    s.push_str("| run-up | TE mean (µrad) | TE ptp (µrad) | largest wheel bearing force (N) | steps | CPU per step (µs) |\n|---|---:|---:|---:|---:|---:|\n");
    let row = |s: &mut String, name: &str, r: &CompliantRunSummary| {
        let most = r.wheel_bearing_force_n.iter().copied().fold(0.0, f64::max);
        let _ = writeln!(
            s,
            "| {name} | {:.2} | {:.2} | {:.0} | {} | {:.1} |",
            r.te_mean_urad,
            r.te_ptp_urad,
            most,
            r.steps,
            r.cpu_s_per_step * 1e6
        );
    };
    row(s, "flexible gearbox", g);
    if let Some(c) = compliant {
        row(s, "compliant bearings, condensed shafts", c);
    }
    s.push('\n');
}

#[cfg(test)]
mod tests {
    use super::*;
    use formats::summaries::{GearboxCrossing, GearboxMode};

    fn run(te: f64, steps: usize, cpu_us: f64) -> CompliantRunSummary {
        CompliantRunSummary {
            case: "run-up".into(),
            torque_nm: 300.0,
            steps,
            rejected_steps: 0,
            cpu_s: cpu_us * 1e-6 * steps as f64,
            cpu_s_per_step: cpu_us * 1e-6,
            te_mean_urad: te,
            te_ptp_urad: 17.5,
            largest_misalignment: [1.0; 4],
            largest_linearization_urad: 0.0,
            mean_linearization_urad: 0.0,
            pinion_bearing_force_n: vec![100.0],
            wheel_bearing_force_n: vec![950.4, 1210.6],
            csv: "x.csv".into(),
        }
    }

    fn summary() -> GearboxSummary {
        GearboxSummary {
            coordinates: 127,
            shaft_mass_kg: [0.986, 1.850],
            shaft_element_mm: 10.0,
            modes_torque_nm: 300.0,
            energy_parts: [
                "pinion turn",
                "wheel turn",
                "pinion body",
                "wheel body",
                "pinion shaft",
                "wheel shaft",
                "housing",
            ]
            .map(String::from)
            .to_vec(),
            modes: vec![
                GearboxMode {
                    frequency_hz: 502.45,
                    energy_share: vec![0.0, 0.788, 0.162, 0.044, 0.006, 0.0, 0.0],
                },
                GearboxMode {
                    frequency_hz: 825.94,
                    energy_share: vec![0.0, 0.0, 0.0, 0.992, 0.0, 0.008, 0.0],
                },
            ],
            crossings: vec![GearboxCrossing {
                mode: 0,
                frequency_hz: 502.45,
                order: 40.0,
                pinion_rpm: 753.67,
            }],
            run: Some(run(1056.15, 19452, 67.9)),
            housing: None,
            notes: vec!["rigid housing".into()],
        }
    }

    fn housing(error_scale: f64) -> formats::summaries::HousingSummary {
        formats::summaries::HousingSummary {
            mass_kg: 23.1,
            nodes: 35_729,
            elements: 19_235,
            least_gap_mm: 10.05,
            seat_nodes: vec![365, 368, 302, 302],
            seats: vec![(0, 0), (0, 1), (1, 0), (1, 1)],
            fixed_interface_modes: 86,
            highest_fixed_interface_hz: 14_949.0,
            modes_up_to_hz: 15_000.0,
            reduced_hz: vec![324.2, 4_850.0 * (1.0 + 0.0047 * error_scale)],
            reference_hz: vec![324.1, 4_850.0],
            truncation_error: 0.0047 * error_scale,
            seat_acceleration_m_s2: vec![1.5, 2.25, 30.0, 12.5],
        }
    }

    /// The housing's lines carry its numbers and judge its reduction by
    /// the 1 % bound, either way; without a housing there are none.
    #[test]
    fn housing_lines_judge_the_reduction_against_the_whole_fe_housing() {
        let mut g = summary();
        let mut s = String::new();
        housing_lines(&mut s, &g);
        assert!(s.is_empty(), "{s}");
        g.housing = Some(housing(1.0));
        housing_lines(&mut s, &g);
        for want in [
            "35729 nodes",
            "23.1 kg",
            "10.1 mm",
            "86 fixed-interface modes up to 14949 Hz",
            "| 1 | 4872.8 | 4850.0 | +0.47 |",
            "Largest difference up to 4850 Hz: 0.47 %, within the 1 %",
            "wheel bearing 0 30.0",
        ] {
            assert!(s.contains(want), "{want} not in {s}");
        }
        g.housing = Some(housing(3.0));
        let mut s = String::new();
        housing_lines(&mut s, &g);
        assert!(
            s.contains("1.41 %, above the 1 % the reduction is held to"),
            "{s}"
        );
    }

    /// The tables carry the summary's numbers, and only the parts some mode
    /// moves (pinion turn held, housing rigid: left out).
    #[test]
    fn gearbox_tables_show_the_summarys_modes_crossings_and_runs() {
        let g = summary();
        let mut s = String::new();
        modes_table(&mut s, &g);
        assert!(
            s.contains("| 0 | 502.4 | 78.8 | 16.2 | 4.4 | 0.6 | 0.0 |"),
            "{s}"
        );
        assert!(!s.contains("pinion turn") && !s.contains("housing"), "{s}");
        assert!(s.contains("wheel shaft (%)"));
        crossings_table(&mut s, &g);
        assert!(s.contains("| 754 | 40.00 | 0 | 502.4 |"), "{s}");
        runs_table(&mut s, g.run.as_ref(), Some(&run(1030.2, 18003, 19.4)));
        assert!(
            s.contains("| flexible gearbox | 1056.15 | 17.50 | 1211 | 19452 | 67.9 |"),
            "{s}"
        );
        assert!(
            s.contains("| compliant bearings, condensed shafts | 1030.20 |"),
            "{s}"
        );
        let mut empty = String::new();
        let none = GearboxSummary {
            modes: vec![],
            crossings: vec![],
            run: None,
            housing: None,
            ..summary()
        };
        modes_table(&mut empty, &none);
        crossings_table(&mut empty, &none);
        runs_table(&mut empty, None, None);
        assert!(
            empty.contains("No mode below")
                && empty.contains("No excitation order")
                && empty.contains("No run-up")
        );
    }

    #[test]
    fn gearbox_section_without_its_summary_says_so_in_one_line() {
        let dir = std::env::temp_dir().join(format!("gearbox_section_{}", std::process::id()));
        let s = section(Some(&dir), &dir);
        assert!(
            s.markdown.contains("No flexible-gearbox runs")
                && s.markdown
                    .contains("solver dynamic reference/scenes/white_paper_gearbox.toml"),
            "{}",
            s.markdown
        );
        assert!(s.figures.is_empty());
        assert!(section(None, &dir)
            .markdown
            .contains("without an output root"));
    }

    fn orders(wheel: geometry::scene::Blank, scale: f64, sidebands: f64) -> RunupOrders {
        let mark = |label: &str, order: f64, f: f64| formats::lumped_summary::MarkedOrder {
            label: label.into(),
            pinion_order: order,
            wheel_bearing_force_n: f,
        };
        RunupOrders {
            pinion_blank: geometry::scene::Blank::Standard,
            wheel_blank: wheel,
            pinion_teeth: 20,
            wheel_teeth: 43,
            samples_per_window: 1376,
            order_resolution: 20.0 / 43.0,
            windows: [480.0, 1010.0]
                .iter()
                .map(|&rpm| formats::summaries::RunupOrderWindow {
                    pinion_rev: [0.0, 2.15],
                    time_s: [0.0, 0.26],
                    mean_pinion_rpm: rpm,
                    pinion_rpm: [rpm - 60.0, rpm + 60.0],
                    marked: vec![
                        mark("20", 20.0, 40.0 * scale),
                        mark("40", 40.0, 30.0),
                        mark("3·20/43", 60.0 / 43.0, 2.0 * scale),
                        mark("20-1.40", 20.0 - 60.0 / 43.0, 0.5 * sidebands),
                        mark("20+1.40", 20.0 + 60.0 / 43.0, 1.5 * sidebands),
                    ],
                })
                .collect(),
        }
    }

    /// The nearest window's amplitudes per model and wheel, and the
    /// lightweight over standard ratios at the hole order and the side
    /// bands; without windows one line.
    #[test]
    fn order_table_gives_the_nearest_windows_and_the_lightweight_ratios() {
        use geometry::scene::Blank;
        let rows = vec![
            (
                "standard".to_string(),
                Some(orders(Blank::Standard, 1.0, 1.0)),
                Some(orders(Blank::Standard, 1.0, 1.0)),
            ),
            (
                "lightweight".to_string(),
                Some(orders(Blank::Lightweight, 1.5, 3.0)),
                None,
            ),
        ];
        let mut s = String::new();
        orders_table(&mut s, &rows, &[500.0]);
        assert!(s.contains("| 500 | standard | flexible gearbox | 480 | 4.000e1 | 3.000e1 | 2.000e0 | 5.000e-1 | 1.500e0 |"), "{s}");
        assert!(
            s.contains("| 500 | lightweight | flexible gearbox | 480 | 6.000e1 |"),
            "{s}"
        );
        assert!(
            s.contains("flexible gearbox at 500 rpm: 1.5 and 3.0"),
            "{s}"
        );
        // The compliant model has no lightweight run: no ratio for it.
        assert!(!s.contains("compliant bearings at 500 rpm"), "{s}");
        let mut empty = String::new();
        let none = vec![(
            "standard".to_string(),
            Some(RunupOrders {
                windows: vec![],
                ..orders(Blank::Standard, 1.0, 1.0)
            }),
            None,
        )];
        orders_table(&mut empty, &none, &[500.0]);
        assert!(empty.contains("No run-up order analysis"), "{empty}");
    }
}
