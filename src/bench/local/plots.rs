//! SVG box plots of a benchmark, one per scene and measure, methods side by side — the plots
//! `ompl_benchmark_statistics.py --plot` draws (boxes at the quartiles, whiskers to the
//! furthest value within 1.5 IQR, the rest as points), written by hand as plain SVG.
//!
//! Runs without a value (they never reached the target) are not drawn; their number is written
//! above the method, as OMPL writes its NaN counts.

use super::report::{first_stage_solving, Report, SceneReport};
use super::run::StageRecord;
use super::BenchError;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// One box: a method's values.
#[derive(Clone, Debug, PartialEq)]
pub struct BoxData {
    /// Method label.
    pub label: String,
    /// The values (runs that have one).
    pub values: Vec<f64>,
    /// Runs without a value.
    pub missing: usize,
}

/// Quartile `p` of sorted `v` with linear interpolation (numpy's default).
pub fn quantile(v: &[f64], p: f64) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    let h = (v.len() - 1) as f64 * p;
    let (lo, hi) = (h.floor() as usize, h.ceil() as usize);
    v[lo] + (h - lo as f64) * (v[hi] - v[lo])
}

/// The five numbers of a box and its outliers: (q1, median, q3, whisker low, whisker high,
/// outliers).
pub fn box_stats(values: &[f64]) -> Option<(f64, f64, f64, f64, f64, Vec<f64>)> {
    let mut v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let (q1, med, q3) = (quantile(&v, 0.25), quantile(&v, 0.5), quantile(&v, 0.75));
    let iqr = q3 - q1;
    let (lo_fence, hi_fence) = (q1 - 1.5 * iqr, q3 + 1.5 * iqr);
    let inside: Vec<f64> = v
        .iter()
        .copied()
        .filter(|&x| x >= lo_fence && x <= hi_fence)
        .collect();
    let wlo = inside.first().copied().unwrap_or(q1);
    let whi = inside.last().copied().unwrap_or(q3);
    let outliers = v
        .into_iter()
        .filter(|&x| x < lo_fence || x > hi_fence)
        .collect();
    Some((q1, med, q3, wlo, whi, outliers))
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Tick values for `[lo, hi]`: 1-2-5 steps on a linear axis, decades on a log axis.
fn ticks(lo: f64, hi: f64, log: bool) -> Vec<f64> {
    if log {
        let (a, b) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
        return (a..=b).map(|k| 10f64.powi(k)).collect();
    }
    let span = (hi - lo).max(f64::MIN_POSITIVE);
    let raw = span / 5.0;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * mag)
        .find(|s| span / s <= 6.0)
        .unwrap_or(10.0 * mag);
    let mut t = (lo / step).floor() * step;
    let mut out = Vec::new();
    while t <= hi + step * 1e-9 {
        out.push(t);
        t += step;
    }
    out
}

fn tick_label(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if v.abs() >= 1e5 || v.abs() < 1e-3 {
        format!("{v:.0e}")
    } else if v.fract() == 0.0 {
        format!("{v:.0}")
    } else {
        format!("{}", (v * 1e4).round() / 1e4)
    }
}

/// A box plot as an SVG document. The axis is logarithmic when every value is positive and
/// they span more than two decades.
pub fn box_plot(title: &str, y_label: &str, data: &[BoxData]) -> String {
    let all: Vec<f64> = data
        .iter()
        .flat_map(|d| d.values.iter().copied())
        .filter(|x| x.is_finite())
        .collect();
    let frame = PlotFrame::new(data, &all);
    let (width, height) = (frame.width, frame.height);
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.0} {height:.0}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(
        s,
        r#"<rect width="100%" height="100%" fill="white"/><text x="{:.1}" y="24" text-anchor="middle" font-size="15">{}</text>"#,
        width / 2.0,
        escape(title)
    );
    frame.y_axis(&mut s, y_label);
    for (k, d) in data.iter().enumerate() {
        frame.one_box(&mut s, k, d);
    }
    s.push_str("</svg>\n");
    s
}

/// Where things go in a box plot: margins sized for the labels, and the value axis.
struct PlotFrame {
    w_box: f64,
    left: f64,
    top: f64,
    right: f64,
    width: f64,
    height: f64,
    plot_h: f64,
    /// The value axis's range and whether it is logarithmic.
    lo: f64,
    hi: f64,
    log: bool,
}

impl PlotFrame {
    /// The frame for boxes `data` of the finite values `all`.
    fn new(data: &[BoxData], all: &[f64]) -> PlotFrame {
        // room below and to the right for the labels, written at 35° (about 7 px per character
        // of 12-px sans-serif): the longest one sets the bottom margin, and each one must end
        // inside the picture, starting from its own box
        let label_px = |d: &BoxData| 7.0 * (d.label.chars().count() + 8) as f64;
        let (cos, sin) = (35f64.to_radians().cos(), 35f64.to_radians().sin());
        let (w_box, left, top) = (90.0, 90.0, 50.0);
        let longest = data.iter().map(label_px).fold(0.0, f64::max);
        let bottom = (longest * sin + 30.0).max(170.0);
        let overhang = data
            .iter()
            .enumerate()
            .map(|(i, d)| label_px(d) * cos - w_box * (data.len() - i) as f64 + w_box / 2.0)
            .fold(0.0, f64::max);
        let right = (overhang + 20.0).max(20.0);
        let width = left + right + w_box * data.len().max(1) as f64;
        let height = top + 260.0 + bottom;
        let plot_h = height - top - bottom;
        let (min, max) = all
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            });
        let log = !all.is_empty() && min > 0.0 && max / min > 100.0;
        let (lo, hi) = if all.is_empty() {
            (0.0, 1.0)
        } else if log {
            (
                10f64.powf(min.log10().floor()),
                10f64.powf(max.log10().ceil()),
            )
        } else {
            let lo = if min >= 0.0 { 0.0 } else { min };
            let hi = if max > lo { max * 1.05 } else { lo + 1.0 };
            (lo, hi)
        };
        PlotFrame {
            w_box,
            left,
            top,
            right,
            width,
            height,
            plot_h,
            lo,
            hi,
            log,
        }
    }

    /// The height in the picture of value `v`.
    fn y(&self, v: f64) -> f64 {
        let (lo, hi) = (self.lo, self.hi);
        let f = if self.log {
            (v.log10() - lo.log10()) / (hi.log10() - lo.log10())
        } else {
            (v - lo) / (hi - lo)
        };
        self.top + self.plot_h * (1.0 - f)
    }

    /// The grid, the value axis and its label.
    fn y_axis(&self, s: &mut String, y_label: &str) {
        let (left, top, right, width, plot_h) =
            (self.left, self.top, self.right, self.width, self.plot_h);
        let (lo, hi, log) = (self.lo, self.hi, self.log);
        let y = |v: f64| self.y(v);
        // grid and y axis
        for t in ticks(lo, hi, log) {
            if t < lo - 1e-12 || t > hi * (1.0 + 1e-12) {
                continue;
            }
            let yy = y(t);
            let _ = writeln!(
                s,
                r##"<line x1="{left}" x2="{:.1}" y1="{yy:.1}" y2="{yy:.1}" stroke="#ddd"/><text x="{:.1}" y="{:.1}" text-anchor="end">{}</text>"##,
                width - right,
                left - 6.0,
                yy + 4.0,
                tick_label(t)
            );
        }
        let _ = writeln!(
            s,
            r#"<line x1="{left}" x2="{left}" y1="{top}" y2="{:.1}" stroke="black"/><text transform="translate(18 {:.1}) rotate(-90)" text-anchor="middle">{}{}</text>"#,
            top + plot_h,
            top + plot_h / 2.0,
            escape(y_label),
            if log { " (log scale)" } else { "" }
        );
    }

    /// Box `k` of the plot: the box and whiskers with the outliers, how many runs are missing,
    /// and its label.
    fn one_box(&self, s: &mut String, k: usize, d: &BoxData) {
        let (w_box, left, top, plot_h) = (self.w_box, self.left, self.top, self.plot_h);
        let y = |v: f64| self.y(v);
        let cx = left + w_box * (k as f64 + 0.5);
        let half = w_box * 0.3;
        if let Some((q1, med, q3, wlo, whi, outliers)) = box_stats(&d.values) {
            let _ = writeln!(
                s,
                r##"<line x1="{cx:.1}" x2="{cx:.1}" y1="{:.1}" y2="{:.1}" stroke="black"/><line x1="{cx:.1}" x2="{cx:.1}" y1="{:.1}" y2="{:.1}" stroke="black"/><line x1="{:.1}" x2="{:.1}" y1="{:.1}" y2="{:.1}" stroke="black"/><line x1="{:.1}" x2="{:.1}" y1="{:.1}" y2="{:.1}" stroke="black"/><rect x="{:.1}" y="{:.1}" width="{:.1}" height="{:.1}" fill="#9ecae1" stroke="black"/><line x1="{:.1}" x2="{:.1}" y1="{:.1}" y2="{:.1}" stroke="#d62728" stroke-width="2"/>"##,
                y(whi),
                y(q3),
                y(q1),
                y(wlo),
                cx - half / 2.0,
                cx + half / 2.0,
                y(whi),
                y(whi),
                cx - half / 2.0,
                cx + half / 2.0,
                y(wlo),
                y(wlo),
                cx - half,
                y(q3),
                2.0 * half,
                (y(q1) - y(q3)).max(0.5),
                cx - half,
                cx + half,
                y(med),
                y(med)
            );
            for o in outliers {
                let _ = writeln!(
                    s,
                    r#"<circle cx="{cx:.1}" cy="{:.1}" r="3" fill="none" stroke="black"/>"#,
                    y(o)
                );
            }
        }
        if d.missing > 0 {
            let _ = writeln!(
                s,
                r##"<text x="{cx:.1}" y="{:.1}" text-anchor="middle" fill="#d62728">{} missing</text>"##,
                top - 6.0,
                d.missing
            );
        }
        let base = top + plot_h + 14.0;
        let _ = writeln!(
            s,
            r#"<text transform="translate({:.1} {base:.1}) rotate(35)" text-anchor="start">{} (n={})</text>"#,
            cx - 6.0,
            escape(&d.label),
            d.values.len()
        );
    }
}

/// File-name-safe form of a scene name.
fn file_stem(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// The boxes of one measure taken at each run's first stage that solved the target share of
/// the solvable queries.
fn at_target(scene: &SceneReport, f: impl Fn(&StageRecord) -> f64) -> Vec<BoxData> {
    scene
        .methods
        .iter()
        .map(|m| {
            let mut values = Vec::new();
            let mut missing = 0;
            for r in scene.runs.iter().filter(|r| r.method == m.method) {
                match first_stage_solving(r, &scene.solvable, scene.solvable_needed) {
                    Some(st) => values.push(f(st)),
                    None => missing += 1,
                }
            }
            BoxData {
                label: m.method.clone(),
                values,
                missing,
            }
        })
        .collect()
}

/// Writes the box plots of every scene into `dir`: learning time, nodes, intersect calls and
/// state checks up to the target share of the solvable queries. Returns the files written.
pub fn write_plots(dir: &Path, report: &Report) -> Result<Vec<PathBuf>, BenchError> {
    let pct = format!("{:.0} %", 100.0 * report.plan.target);
    let mut written = Vec::new();
    for scene in &report.scenes {
        let stem = file_stem(&scene.info.name);
        let plots: [(&str, String, &str, Vec<BoxData>); 4] = [
            (
                "time",
                format!("{}: learning time to {pct} of the queries", scene.info.name),
                "seconds",
                at_target(scene, |s| s.learn_seconds),
            ),
            (
                "nodes",
                format!("{}: roadmap nodes at {pct} of the queries", scene.info.name),
                "nodes",
                at_target(scene, |s| s.nodes as f64),
            ),
            (
                "calls",
                format!(
                    "{}: intersect calls of learning to {pct} of the queries",
                    scene.info.name
                ),
                "segment + line calls",
                at_target(scene, |s| s.counts.intersect_calls() as f64),
            ),
            (
                "state-checks",
                format!(
                    "{}: state checks of learning to {pct} of the queries",
                    scene.info.name
                ),
                "state checks",
                at_target(scene, |s| s.counts.state_checks as f64),
            ),
        ];
        for (what, title, axis, boxes) in plots {
            let path = dir.join(format!("{stem}-{what}.svg"));
            let svg = box_plot(&title, axis, &boxes);
            crate::safe_file::write_atomically(&path, |w| w.write_all(svg.as_bytes()))?;
            written.push(path);
        }
    }
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quartiles_and_whiskers_follow_matplotlib() {
        // numpy: percentile([1..9], 25/50/75) = 3, 5, 7; 100 is beyond q3 + 1.5·IQR = 13
        let v = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 100.0];
        let (q1, m, q3, lo, hi, out) = box_stats(&v).unwrap();
        assert_eq!((q1, m, q3), (3.0, 5.0, 7.0));
        assert_eq!((lo, hi), (1.0, 8.0));
        assert_eq!(out, vec![100.0]);
        assert_eq!(quantile(&[1.0, 2.0], 0.5), 1.5);
        assert!(box_stats(&[]).is_none());
    }

    #[test]
    fn plots_are_svg_with_one_box_per_method() {
        let data = vec![
            BoxData {
                label: "a<b".into(),
                values: vec![1.0, 2.0, 3.0],
                missing: 0,
            },
            BoxData {
                label: "c".into(),
                values: vec![1000.0, 2000.0],
                missing: 2,
            },
        ];
        let svg = box_plot("t", "s", &data);
        assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
        assert_eq!(svg.matches("<rect").count(), 3); // background + two boxes
        assert!(svg.contains("a&lt;b (n=3)"));
        assert!(svg.contains("2 missing"));
        assert!(svg.contains("log scale"));
        assert_eq!(ticks(0.0, 10.0, false), vec![0.0, 2.0, 4.0, 6.0, 8.0, 10.0]);
    }
}
