//! Spectrogram of a run-up signal: short-time Fourier transform with a Hann
//! window, evaluated at the frequencies of interest only, and its SVG
//! picture with the pinion's order lines drawn over it.

use plotters::prelude::*;
use std::path::Path;

/// Amplitudes |X(t, f)| of a signal sampled at uniform `dt`.
#[derive(Debug, Clone)]
pub struct Spectrogram {
    /// Window centres, s.
    pub time: Vec<f64>,
    /// Frequencies, Hz.
    pub freq: Vec<f64>,
    /// Single-sided amplitude (signal units), row-major time × freq.
    pub amp: Vec<f64>,
}

/// Linear resampling of (t, y) at uniform `dt` from t[0].
pub fn resample(t: &[f64], y: &[f64], dt: f64) -> Vec<f64> {
    let (Some(&t0), Some(&t1)) = (t.first(), t.last()) else {
        return Vec::new();
    };
    let n = ((t1 - t0) / dt).floor() as usize + 1;
    let mut k = 1;
    (0..n)
        .map(|i| {
            let x = t0 + dt * i as f64;
            while k + 1 < t.len() && t[k] < x {
                k += 1;
            }
            let (a, b) = (k.saturating_sub(1), k.min(t.len() - 1));
            if a == b || t[b] == t[a] {
                y[a]
            } else {
                y[a] + (y[b] - y[a]) * (x - t[a]) / (t[b] - t[a])
            }
        })
        .collect()
}

/// STFT of `y` (uniform `dt`): windows of `window` samples every `hop`
/// samples, mean removed per window, Hann-weighted, amplitude scaled so that
/// a sine of amplitude A inside a window shows A at its frequency.
pub fn stft(y: &[f64], dt: f64, window: usize, hop: usize, freq: &[f64]) -> Spectrogram {
    let hann: Vec<f64> = (0..window)
        .map(|i| 0.5 - 0.5 * (2.0 * std::f64::consts::PI * i as f64 / window as f64).cos())
        .collect();
    let wsum: f64 = hann.iter().sum();
    let mut time = Vec::new();
    let mut amp = Vec::new();
    let mut start = 0;
    while start + window <= y.len() {
        let seg = &y[start..start + window];
        let mean = seg.iter().sum::<f64>() / window as f64;
        for &f in freq {
            let w = 2.0 * std::f64::consts::PI * f * dt;
            let (mut re, mut im) = (0.0, 0.0);
            for (i, (&v, &h)) in seg.iter().zip(&hann).enumerate() {
                let (s, c) = (w * i as f64).sin_cos();
                re += (v - mean) * h * c;
                im -= (v - mean) * h * s;
            }
            amp.push(2.0 * (re * re + im * im).sqrt() / wsum);
        }
        time.push(dt * (start as f64 + 0.5 * window as f64));
        start += hop;
    }
    Spectrogram {
        time,
        freq: freq.to_vec(),
        amp,
    }
}

/// An order line: f = order × pinion speed (Hz per rev/s).
pub struct OrderLine {
    pub order: f64,
    pub label: String,
}

/// Draws the spectrogram (dB re the largest amplitude, 60 dB range) with the
/// order lines over it; `pinion_hz(t)` is the pinion speed in rev/s.
pub fn plot(
    path: &Path,
    title: &str,
    s: &Spectrogram,
    pinion_hz: &dyn Fn(f64) -> f64,
    orders: &[OrderLine],
) -> anyhow::Result<()> {
    plot_with_modes(path, title, s, pinion_hz, orders, &[])
}

/// [`plot`] with the system's natural frequencies `modes_hz` as dashed
/// horizontal lines (a Campbell diagram over the spectrogram: where an
/// order line crosses one, that order meets that mode).
pub fn plot_with_modes(
    path: &Path,
    title: &str,
    s: &Spectrogram,
    pinion_hz: &dyn Fn(f64) -> f64,
    orders: &[OrderLine],
    modes_hz: &[f64],
) -> anyhow::Result<()> {
    let (nt, nf) = (s.time.len(), s.freq.len());
    anyhow::ensure!(
        nt >= 2 && nf >= 2,
        "spectrogram {}: too few windows",
        path.display()
    );
    let peak = s
        .amp
        .iter()
        .copied()
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (900, 560)).into_drawing_area();
        root.fill(&WHITE)?;
        let (t0, t1) = (s.time[0], s.time[nt - 1]);
        let (f0, f1) = (s.freq[0], s.freq[nf - 1]);
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(t0..t1, f0..f1)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("time (s)")
            .y_desc("frequency (Hz)")
            .label_style(("sans-serif", 12))
            .draw()?;
        let dtw = (t1 - t0) / (nt - 1) as f64;
        let dfw = (f1 - f0) / (nf - 1) as f64;
        chart.draw_series((0..nt).flat_map(|i| {
            (0..nf).map(move |k| {
                let db = 20.0 * (s.amp[i * nf + k] / peak).max(1e-3).log10();
                let x = (1.0 + db / 60.0).clamp(0.0, 1.0);
                let c = HSLColor(0.7 * (1.0 - x), 0.9, 0.1 + 0.45 * x);
                Rectangle::new(
                    [
                        (s.time[i] - 0.5 * dtw, s.freq[k] - 0.5 * dfw),
                        (s.time[i] + 0.5 * dtw, s.freq[k] + 0.5 * dfw),
                    ],
                    c.filled(),
                )
            })
        }))?;
        for o in orders {
            let pts: Vec<(f64, f64)> = (0..=100)
                .map(|k| {
                    let t = t0 + (t1 - t0) * k as f64 / 100.0;
                    (t, o.order * pinion_hz(t))
                })
                .filter(|p| p.1 <= f1)
                .collect();
            if let Some(&last) = pts.last() {
                chart.draw_series(LineSeries::new(pts, WHITE.stroke_width(1)))?;
                chart.draw_series(std::iter::once(Text::new(
                    o.label.clone(),
                    last,
                    ("sans-serif", 12).into_font().color(&WHITE),
                )))?;
            }
        }
        for &f in modes_hz.iter().filter(|&&f| f > f0 && f < f1) {
            chart.draw_series(DashedLineSeries::new(
                [(t0, f), (t1, f)],
                6,
                4,
                WHITE.mix(0.7).stroke_width(1),
            ))?;
        }
        root.present()?;
    }
    formats::output::write_atomic(path, svg.as_bytes())?;
    Ok(())
}

/// Draws an order map: one row per pinion speed (`speeds_rpm`, ascending),
/// the amplitude `amp[row][k]` at pinion order `orders[k]` in dB re the
/// largest (60 dB range), each row a band reaching half-way to its
/// neighbours, with the marked orders as labelled ticks along the top.
pub fn plot_order_map(
    path: &Path,
    title: &str,
    orders: &[f64],
    speeds_rpm: &[f64],
    amp: &[Vec<f64>],
    marks: &[OrderLine],
) -> anyhow::Result<()> {
    let (nr, no) = (speeds_rpm.len(), orders.len());
    anyhow::ensure!(
        nr >= 1 && no >= 2 && amp.len() == nr && amp.iter().all(|r| r.len() == no),
        "order map {}: {nr} speeds, {no} orders, {} rows",
        path.display(),
        amp.len()
    );
    let peak = amp
        .iter()
        .flatten()
        .copied()
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let edge = |i: usize| -> [f64; 2] {
        let s = speeds_rpm[i];
        let lo = if i > 0 {
            0.5 * (s + speeds_rpm[i - 1])
        } else {
            s - 0.5 * if nr > 1 { speeds_rpm[1] - s } else { 0.1 * s }
        };
        let hi = if i + 1 < nr {
            0.5 * (s + speeds_rpm[i + 1])
        } else {
            s + 0.5
                * if nr > 1 {
                    s - speeds_rpm[nr - 2]
                } else {
                    0.1 * s
                }
        };
        [lo, hi]
    };
    let (y0, y1) = (edge(0)[0], edge(nr - 1)[1]);
    let (o0, o1) = (orders[0], orders[no - 1]);
    let dor = (o1 - o0) / (no - 1) as f64;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (900, 480)).into_drawing_area();
        root.fill(&WHITE)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(o0 - 0.5 * dor..o1 + 0.5 * dor, y0..y1)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("pinion order")
            .y_desc("pinion speed (rpm)")
            .label_style(("sans-serif", 12))
            .draw()?;
        chart.draw_series((0..nr).flat_map(|i| {
            let [lo, hi] = edge(i);
            (0..no).map(move |k| {
                let db = 20.0 * (amp[i][k] / peak).max(1e-3).log10();
                let x = (1.0 + db / 60.0).clamp(0.0, 1.0);
                let c = HSLColor(0.7 * (1.0 - x), 0.9, 0.1 + 0.45 * x);
                Rectangle::new(
                    [(orders[k] - 0.5 * dor, lo), (orders[k] + 0.5 * dor, hi)],
                    c.filled(),
                )
            })
        }))?;
        for m in marks.iter().filter(|m| m.order >= o0 && m.order <= o1) {
            // A tick along the top only: the lines under it stay visible.
            chart.draw_series(LineSeries::new(
                [(m.order, y1 - 0.05 * (y1 - y0)), (m.order, y1)],
                WHITE.stroke_width(1),
            ))?;
            chart.draw_series(std::iter::once(Text::new(
                m.label.clone(),
                (m.order, y1),
                ("sans-serif", 11).into_font().color(&WHITE),
            )))?;
        }
        root.present()?;
    }
    formats::output::write_atomic(path, svg.as_bytes())?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sine_shows_its_amplitude_at_its_frequency_only() {
        let dt = 1e-4;
        let y: Vec<f64> = (0..4000)
            .map(|i| 3.0 + 2.0 * (2.0 * std::f64::consts::PI * 250.0 * dt * i as f64).sin())
            .collect();
        let s = stft(&y, dt, 1000, 500, &[100.0, 250.0, 400.0]);
        for w in 0..s.time.len() {
            let a = &s.amp[w * 3..w * 3 + 3];
            assert!((a[1] - 2.0).abs() < 1e-3, "{a:?}");
            assert!(a[0] < 1e-3 && a[2] < 1e-3, "{a:?}");
        }
    }

    #[test]
    fn resampling_a_line_is_exact() {
        let t = [0.0, 0.3, 0.35, 1.0];
        let y: Vec<f64> = t.iter().map(|x| 2.0 * x + 1.0).collect();
        let r = resample(&t, &y, 0.1);
        assert_eq!(r.len(), 11);
        for (i, v) in r.iter().enumerate() {
            assert!((v - (0.2 * i as f64 + 1.0)).abs() < 1e-12);
        }
    }
}
