//! One stage's run time against error: the settings a stage was
//! run at, each with its cost and its error to a converged value, the
//! setting that reaches [`TARGET_PCT`] at the least cost and whether the
//! default is it; charted by [`charts::pareto_chart`].

use charts::{pareto_chart, ParetoPoint, ParetoSeries};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The error every stage is asked to reach, percent.
pub const TARGET_PCT: f64 = 1.0;

/// One setting of one parameter.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TradeoffPoint {
    /// The parameter varied (the others at their defaults).
    pub parameter: String,
    /// The setting, as a user writes it.
    pub setting: String,
    /// Its numeric value (for ordering).
    pub value: f64,
    /// Cost, s (what it measures: [`StageTradeoff::cost`]).
    pub cpu_s: f64,
    /// Error to the converged value, percent ([`StageTradeoff::error`]).
    pub error_pct: f64,
    /// A second error measure where the stage has one (e.g. the peak-to-peak
    /// TE beside the mean), percent.
    #[serde(default)]
    pub secondary_error_pct: Option<f64>,
    /// The scene's (or the toolkit's) default setting.
    pub is_default: bool,
}

/// A setting that could not be run or compared, with why.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NotRun {
    pub parameter: String,
    pub setting: String,
    pub reason: String,
}

/// One stage.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StageTradeoff {
    /// Short name: "utca", "stiffness", "ltca", "multibody", "reference".
    pub stage: String,
    pub title: String,
    /// What `cpu_s` measures.
    pub cost: String,
    /// What `error_pct` measures, and against what.
    pub error: String,
    pub points: Vec<TradeoffPoint>,
    pub not_run: Vec<NotRun>,
    pub target_pct: f64,
    /// The cheapest point with error ≤ the target; None when none reaches it.
    pub cheapest: Option<TradeoffPoint>,
    /// The default's first point.
    pub default: Option<TradeoffPoint>,
    /// Whether the cheapest point within the target is a default point
    /// (None when no point reaches the target or there is no default).
    pub default_is_cheapest: Option<bool>,
    /// Chart file name beside the JSON, when drawn.
    pub chart: Option<String>,
}

impl StageTradeoff {
    pub fn new(stage: &str, title: &str, cost: &str, error: &str) -> Self {
        StageTradeoff {
            stage: stage.into(),
            title: title.into(),
            cost: cost.into(),
            error: error.into(),
            points: Vec::new(),
            not_run: Vec::new(),
            target_pct: TARGET_PCT,
            cheapest: None,
            default: None,
            default_is_cheapest: None,
            chart: None,
        }
    }

    /// Records a point (a non-finite cost or error becomes a [`NotRun`]).
    pub fn push(&mut self, p: TradeoffPoint) {
        if p.cpu_s.is_finite() && p.error_pct.is_finite() {
            self.points.push(p);
        } else {
            self.not_run.push(NotRun {
                reason: format!(
                    "non-finite result: cost {} s, error {} %",
                    p.cpu_s, p.error_pct
                ),
                parameter: p.parameter,
                setting: p.setting,
            });
        }
    }

    pub fn skip(&mut self, parameter: &str, setting: &str, reason: String) {
        self.not_run.push(NotRun {
            parameter: parameter.into(),
            setting: setting.into(),
            reason,
        });
    }

    /// Chooses the cheapest point within the target and compares the default.
    pub fn finish(&mut self) {
        self.cheapest = self
            .points
            .iter()
            .filter(|p| p.error_pct.abs() <= self.target_pct)
            .min_by(|a, b| a.cpu_s.total_cmp(&b.cpu_s))
            .cloned();
        self.default = self.points.iter().find(|p| p.is_default).cloned();
        self.default_is_cheapest = match (&self.cheapest, &self.default) {
            (Some(c), Some(_)) => Some(c.is_default),
            _ => None,
        };
    }

    /// The sentence the report prints.
    pub fn verdict(&self) -> String {
        let d = match &self.default {
            Some(d) => format!(
                "the default ({} = {}) costs {} s at {:.3} %",
                d.parameter,
                d.setting,
                sig(d.cpu_s),
                d.error_pct.abs()
            ),
            None => "no default setting was run".into(),
        };
        match (&self.cheapest, self.default_is_cheapest) {
            (None, _) => format!("no setting reaches {} %; {d}", self.target_pct),
            (Some(_), Some(true)) => format!(
                "the default is the cheapest setting within {} %: {d}",
                self.target_pct
            ),
            (Some(c), _) => format!(
                "cheapest within {} %: {} = {} ({} s, {:.3} %); {d}",
                self.target_pct,
                c.parameter,
                c.setting,
                sig(c.cpu_s),
                c.error_pct.abs()
            ),
        }
    }

    /// Draws the chart to `dir/<stage>.svg` when there are points.
    pub fn draw(&mut self, dir: &Path) -> anyhow::Result<()> {
        if self.points.is_empty() {
            return Ok(());
        }
        let mut series: Vec<ParetoSeries> = Vec::new();
        for p in &self.points {
            let pt = ParetoPoint {
                cost: p.cpu_s,
                error: p.error_pct.abs(),
                label: p.setting.clone(),
                is_default: p.is_default,
            };
            match series.iter_mut().find(|s| s.name == p.parameter) {
                Some(s) => s.points.push(pt),
                None => series.push(ParetoSeries {
                    name: p.parameter.clone(),
                    points: vec![pt],
                }),
            }
        }
        let file = format!("{}.svg", self.stage);
        pareto_chart(
            &dir.join(&file),
            &self.title,
            &format!("{} (log)", self.cost_axis()),
            "|error| (%, log)",
            self.target_pct,
            &series,
        )?;
        self.chart = Some(file);
        Ok(())
    }

    fn cost_axis(&self) -> &str {
        self.cost.split(':').next().unwrap_or(&self.cost)
    }
}

/// Four significant digits.
pub fn sig(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let d = (3 - x.abs().log10().floor() as i32).max(0) as usize;
    format!("{x:.d$}")
}

/// Relative error in percent, (value − reference) / |reference|.
pub fn rel_pct(value: f64, reference: f64) -> f64 {
    (value - reference) / reference.abs() * 100.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pt(parameter: &str, cpu_s: f64, error_pct: f64, is_default: bool) -> TradeoffPoint {
        TradeoffPoint {
            parameter: parameter.into(),
            setting: format!("{cpu_s}"),
            value: cpu_s,
            cpu_s,
            error_pct,
            secondary_error_pct: None,
            is_default,
        }
    }

    #[test]
    fn cheapest_within_target_is_named_and_compared_with_the_default() {
        let mut s = StageTradeoff::new("x", "x", "CPU", "err");
        s.push(pt("a", 1.0, 5.0, false));
        s.push(pt("a", 2.0, -0.5, false));
        s.push(pt("a", 4.0, 0.1, true));
        s.push(pt("b", f64::NAN, 0.1, false));
        s.finish();
        assert_eq!(s.cheapest.as_ref().map(|c| c.cpu_s), Some(2.0));
        assert_eq!(s.default_is_cheapest, Some(false));
        assert_eq!(s.not_run.len(), 1);
        assert!(s.verdict().starts_with("cheapest within 1 %: a = 2"));
    }

    #[test]
    fn no_setting_within_target_gives_no_verdict_on_the_default() {
        let mut s = StageTradeoff::new("x", "x", "CPU", "err");
        s.push(pt("a", 1.0, 5.0, true));
        s.finish();
        assert_eq!(s.cheapest, None);
        assert_eq!(s.default_is_cheapest, None);
        assert!(s.verdict().starts_with("no setting reaches 1 %"));
    }
}
