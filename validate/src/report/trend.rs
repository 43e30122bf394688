//! The direction of a sequence of values, step by step: the one test
//! behind the report's "grows with every …" / "falls with every …"
//! sentences, so that such a sentence comes from the numbers it describes.

/// How a sequence changes from each value to the next.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Trend {
    /// Fewer than two values.
    Single,
    /// Every step up.
    Rises,
    /// Every step down.
    Falls,
    /// Steps of both signs, or a step of zero.
    Neither,
}

/// The [`Trend`] of `values` in their order.
pub fn trend(values: &[f64]) -> Trend {
    let steps: Vec<f64> = values.windows(2).map(|w| w[1] - w[0]).collect();
    if steps.is_empty() {
        Trend::Single
    } else if steps.iter().all(|d| *d > 0.0) {
        Trend::Rises
    } else if steps.iter().all(|d| *d < 0.0) {
        Trend::Falls
    } else {
        Trend::Neither
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_step_decides_the_trend() {
        assert_eq!(trend(&[1.0, 2.0, 3.0]), Trend::Rises);
        assert_eq!(trend(&[3.0, 2.0]), Trend::Falls);
        assert_eq!(trend(&[1.0, 3.0, 2.0]), Trend::Neither);
        assert_eq!(trend(&[1.0, 1.0]), Trend::Neither);
        assert_eq!(trend(&[1.0]), Trend::Single);
    }
}
