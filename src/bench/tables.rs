//! Tables A.1–A.4 of the seed, regenerated on the random disc problems of [`super::discs`].
//!
//! Each row is one planner configuration run on the same problem set. As in the seed, the two
//! measures are the number of intersect calls (segment and line calls) and the minimal
//! recursion depth that allows a solution; both are reported as maximum and mean. Unsolved
//! problems — the seed's "start of 1st interval" row lost 173 to its depth limit of 10, and
//! here a per-problem call budget applies — count towards the calls but not towards the depth
//! statistics, exactly as the seed counts them (footnote of Table A.4).

use super::discs::{DiscProblem, GOAL, START};
use crate::local::viapoint::{BasePoint, Depth, ViaLimit, ViaPoint, ViaPointOptions};
use crate::local::{LocalMethod, Outcome};
use rayon::prelude::*;
use serde::Serialize;
use std::fmt::Write as _;

/// Intersect calls one problem may spend, so that a few pathological problems do not dominate
/// the run (the seed's β = 2 run took four and a half days; its largest count was 2·10⁷).
/// Unsolved problems count with the calls they spent, as in the seed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Budgets {
    /// Plain recursion (fixed depth, deepening without re-use): memory stays small.
    pub plain: u64,
    /// Deepening with a tree of subproblems, whose memory grows with the calls.
    pub reuse: u64,
}

impl Default for Budgets {
    /// 10⁵ and 2·10⁵ calls: the whole benchmark runs in under a minute on two cores, and
    /// fewer than one problem in a hundred hits a budget in any row but β = 2.
    fn default() -> Self {
        Budgets {
            plain: 100_000,
            reuse: 200_000,
        }
    }
}

impl Budgets {
    /// The same budget for both.
    pub fn both(calls: u64) -> Self {
        Budgets {
            plain: calls,
            reuse: calls,
        }
    }
}
/// Largest recursion limit tried by deepening (none of the seed's rows needed more than 20).
pub const MAX_DEPTH: u32 = 30;

/// The seed's published numbers for one row (`None`: not given, "?").
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Published {
    /// Maximal minimal recursion depth.
    pub depth_max: Option<f64>,
    /// Mean minimal recursion depth.
    pub depth_mean: Option<f64>,
    /// Maximal number of intersect calls.
    pub calls_max: Option<f64>,
    /// Mean number of intersect calls.
    pub calls_mean: Option<f64>,
}

const fn p(depth_max: f64, depth_mean: f64, calls_max: f64, calls_mean: f64) -> Published {
    Published {
        depth_max: Some(depth_max),
        depth_mean: Some(depth_mean),
        calls_max: Some(calls_max),
        calls_mean: Some(calls_mean),
    }
}

const fn calls_only(calls_max: f64, calls_mean: f64) -> Published {
    Published {
        depth_max: None,
        depth_mean: None,
        calls_max: Some(calls_max),
        calls_mean: Some(calls_mean),
    }
}

const UNKNOWN: Published = Published {
    depth_max: None,
    depth_mean: None,
    calls_max: None,
    calls_mean: None,
};

/// What we measured for one row.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct Measured {
    /// Problems run.
    pub problems: u64,
    /// Problems solved.
    pub solved: u64,
    /// Maximal recursion depth over the solved problems.
    pub depth_max: u32,
    /// Mean recursion depth over the solved problems.
    pub depth_mean: f64,
    /// Maximal intersect calls over all problems.
    pub calls_max: u64,
    /// Mean intersect calls over all problems (the seed's convention: unsolved problems count
    /// with the calls they spent).
    pub calls_mean: f64,
    /// Mean intersect calls over the solved problems only (a budget-capped problem can
    /// dominate the mean over all).
    pub calls_mean_solved: f64,
    /// CPU time the row's problems took, in seconds (summed over threads).
    pub seconds: f64,
}

/// One row of one table.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    /// "A.1" … "A.4".
    pub table: &'static str,
    /// The row's label in the seed (a β value or a base point).
    pub label: String,
    /// Column group: "≤ 2 via points" or "all via points" (A.1–A.3).
    pub via: &'static str,
    /// The planner configuration.
    #[serde(skip)]
    pub options: ViaPointOptions,
    /// The configuration as a spec string.
    pub spec: String,
    /// The seed's numbers.
    pub published: Published,
    /// Ours.
    pub measured: Measured,
}

fn beta_label(b: f64) -> String {
    for (num, den) in [(0, 1), (2, 5), (1, 2), (4, 7), (2, 3), (1, 1), (2, 1)] {
        if (b - num as f64 / den as f64).abs() < 1e-12 {
            return if den == 1 {
                num.to_string()
            } else {
                format!("{num}/{den}")
            };
        }
    }
    format!("{b}")
}

/// The configurations of Tables A.1–A.4 with the seed's numbers.
pub fn rows(budgets: Budgets) -> Vec<Row> {
    let mut tables = Tables {
        base: ViaPointOptions {
            discoveries: false,
            ..ViaPointOptions::seed_experiment()
        },
        budgets,
        rows: Vec::new(),
    };
    tables.a1();
    tables.a2();
    tables.a3();
    tables.a4();
    tables.rows
}

/// The rows of the tables as they are listed, and what their configurations share.
struct Tables {
    base: ViaPointOptions,
    budgets: Budgets,
    rows: Vec<Row>,
}

impl Tables {
    /// A row of `table` with the seed's numbers `published`.
    fn add(
        &mut self,
        table: &'static str,
        label: String,
        via: ViaLimit,
        options: ViaPointOptions,
        published: Published,
    ) {
        let spec = crate::local::LocalSpec::ViaPoint(options.clone()).to_string();
        self.rows.push(Row {
            table,
            label,
            via: if via == ViaLimit::All {
                "all via points"
            } else {
                "≤ 2 via points"
            },
            options,
            spec,
            published,
            measured: Measured::default(),
        });
    }

    /// Iterative deepening without re-use.
    fn plain(&self, beta: f64, via: ViaLimit) -> ViaPointOptions {
        ViaPointOptions {
            beta,
            via,
            depth: Depth::Deepen { max: MAX_DEPTH },
            max_calls: Some(self.budgets.plain),
            ..self.base.clone()
        }
    }

    /// Iterative deepening re-using a tree of solved subproblems.
    fn reuse(&self, beta: f64, via: ViaLimit) -> ViaPointOptions {
        ViaPointOptions {
            beta,
            via,
            depth: Depth::DeepenReuse { max: MAX_DEPTH },
            max_calls: Some(self.budgets.reuse),
            ..self.base.clone()
        }
    }

    /// A fixed recursion depth `k`.
    fn fixed(&self, beta: f64, via: ViaLimit, k: u32) -> ViaPointOptions {
        ViaPointOptions {
            beta,
            via,
            depth: Depth::Fixed(k),
            max_calls: Some(self.budgets.plain),
            ..self.base.clone()
        }
    }

    /// Table A.1: variation of β with minimal recursion depth (iterative deepening).
    fn a1(&mut self) {
        let (two, all) = (ViaLimit::Best(2), ViaLimit::All);
        for (b, two_p, all_p) in [
            (
                0.0,
                p(9.0, 4.606, 3362.0, 194.4),
                p(6.0, 3.812, 3688.0, 321.2),
            ),
            (
                0.5,
                p(7.0, 4.471, 1039.0, 167.0),
                p(6.0, 3.812, 4246.0, 304.5),
            ),
            (
                2.0 / 3.0,
                p(8.0, 4.463, 1937.0, 167.6),
                p(6.0, 3.812, 4367.0, 302.6),
            ),
            (
                1.0,
                p(9.0, 4.573, 7655.0, 194.8),
                p(6.0, 3.812, 3808.0, 308.4),
            ),
            (2.0, p(20.0, 5.528, 2e7, 2e4), p(6.0, 3.812, 4545.0, 339.8)),
        ] {
            self.add("A.1", beta_label(b), two, self.plain(b, two), two_p);
            self.add("A.1", beta_label(b), all, self.plain(b, all), all_p);
        }
    }

    /// Table A.2: the same, re-using a tree of solved subproblems.
    fn a2(&mut self) {
        let (two, all) = (ViaLimit::Best(2), ViaLimit::All);
        for (b, two_p, all_p) in [
            (
                0.5,
                p(7.0, 4.471, 557.0, 94.0),
                p(6.0, 3.812, 3609.0, 236.8),
            ),
            (
                2.0 / 3.0,
                p(8.0, 4.463, 1084.0, 93.9),
                p(6.0, 3.812, 3649.0, 234.5),
            ),
            (
                1.0,
                p(9.0, 4.573, 2939.0, 106.2),
                p(6.0, 3.812, 3033.0, 234.6),
            ),
        ] {
            self.add("A.2", beta_label(b), two, self.reuse(b, two), two_p);
            self.add("A.2", beta_label(b), all, self.reuse(b, all), all_p);
        }
    }

    /// Table A.3: fixed recursion depth, nine with ≤ 2 via points, six with all.
    fn a3(&mut self) {
        let (two, all) = (ViaLimit::Best(2), ViaLimit::All);
        for (b, two_p, all_p) in [
            (0.0, calls_only(3069.0, 94.74), calls_only(7306.0, 149.2)),
            (0.4, calls_only(1933.0, 51.04), UNKNOWN),
            (0.5, calls_only(1793.0, 47.26), calls_only(4178.0, 90.33)),
            (
                4.0 / 7.0,
                calls_only(1802.0, 46.41),
                calls_only(3961.0, 86.49),
            ),
            (
                2.0 / 3.0,
                calls_only(1837.0, 45.97),
                calls_only(3633.0, 83.38),
            ),
            (1.0, calls_only(3159.0, 72.19), calls_only(2056.0, 90.52)),
        ] {
            self.add("A.3", beta_label(b), two, self.fixed(b, two, 9), two_p);
            self.add("A.3", beta_label(b), all, self.fixed(b, all, 6), all_p);
        }
    }

    /// Table A.4: base points of the borderline (β = 2/3, ≤ 2 via points, re-use).
    fn a4(&mut self) {
        let two = ViaLimit::Best(2);
        for (bp, pubd) in [
            (BasePoint::StartOfFirst, p(10.0, 5.972, 9086.0, 547.6)),
            (BasePoint::RandomInFirst, p(8.0, 4.612, 806.0, 106.8)),
            (BasePoint::CentreOfFirst, p(8.0, 4.463, 1084.0, 93.9)),
            (BasePoint::CentreOfRandom, p(7.0, 4.026, 440.0, 64.9)),
            (BasePoint::CentreOfMiddle, p(7.0, 3.649, 591.0, 53.2)),
            (BasePoint::CentreNearestMiddle, p(7.0, 3.616, 581.0, 51.3)),
            (BasePoint::MiddleOfMotion, p(9.0, 4.380, 1359.0, 89.6)),
            (BasePoint::RandomInMotion, p(12.0, 5.972, 5375.0, 211.0)),
        ] {
            let mut o = self.reuse(2.0 / 3.0, two);
            o.base_point = bp;
            if bp == BasePoint::StartOfFirst {
                // the seed: "recursion depth had to be limited to 10"
                o.depth = Depth::DeepenReuse { max: 10 };
            }
            self.add("A.4", bp.description().to_string(), two, o, pubd);
        }
    }
}

/// Runs every row on problems `0..problems` of the set generated with `seed` and disc
/// `radius`, calling `tick` after each (row, problem) pair from any thread. All pairs form one
/// parallel job list over problems generated once, so a row's slowest problem does not leave
/// the other threads idle; each row's `seconds` is the CPU time its problems took.
///
/// Fails (before any row runs) if the generator finds no solvable problem at `radius`
/// ([`super::discs::try_problem`]).
pub fn run_rows(
    rows: &mut [Row],
    problems: u64,
    seed: u64,
    radius: f64,
    tick: &(dyn Fn() + Sync),
) -> Result<(), super::discs::NoSolvableProblem> {
    let space = DiscProblem::space();
    let methods: Vec<ViaPoint> = rows
        .iter()
        .map(|r| ViaPoint::new(r.options.clone()))
        .collect();
    let set: Vec<_> = (0..problems)
        .into_par_iter()
        .map(|i| super::discs::try_problem(seed, i, radius).map(|p| p.oracle()))
        .collect::<Result<_, _>>()?;
    let jobs: Vec<(usize, usize)> = (0..rows.len())
        .flat_map(|r| (0..set.len()).map(move |p| (r, p)))
        .collect();
    let results: Vec<(bool, u32, u64, f64)> = jobs
        .par_iter()
        .map(|&(r, p)| {
            let start = std::time::Instant::now();
            let c = methods[r]
                .connect(&space, &set[p], &START, &GOAL)
                .expect("the disc oracle answers every straight motion");
            tick();
            (
                c.outcome == Outcome::Connected,
                c.depth,
                c.counts.intersect_calls(),
                start.elapsed().as_secs_f64(),
            )
        })
        .collect();
    for (r, row) in rows.iter_mut().enumerate() {
        let mine = &results[r * set.len()..(r + 1) * set.len()];
        let solved: Vec<&(bool, u32, u64, f64)> = mine.iter().filter(|x| x.0).collect();
        row.measured = Measured {
            problems,
            solved: solved.len() as u64,
            depth_max: solved.iter().map(|x| x.1).max().unwrap_or(0),
            depth_mean: solved.iter().map(|x| x.1 as f64).sum::<f64>() / solved.len().max(1) as f64,
            calls_max: mine.iter().map(|x| x.2).max().unwrap_or(0),
            calls_mean: mine.iter().map(|x| x.2 as f64).sum::<f64>() / problems.max(1) as f64,
            calls_mean_solved: solved.iter().map(|x| x.2 as f64).sum::<f64>()
                / solved.len().max(1) as f64,
            seconds: mine.iter().map(|x| x.3).sum(),
        };
    }
    Ok(())
}

fn opt(v: Option<f64>, digits: usize) -> String {
    match v {
        None => "?".into(),
        Some(x) if x >= 1e6 => format!("{x:.0e}"),
        Some(x) => format!("{x:.digits$}"),
    }
}

/// The rows as Markdown tables in the seed's layout, ours beside the seed's ("seed" columns).
pub fn markdown(rows: &[Row]) -> String {
    let mut out = String::new();
    for (table, title, depth_cols) in [
        ("A.1", "Table A.1: variation of β with minimal recursion depth", true),
        ("A.2", "Table A.2: variation of β with minimal recursion depth re-using information", true),
        ("A.3", "Table A.3: variation of β with fixed recursion depth (9 with ≤ 2 via points, 6 with all)", false),
        ("A.4", "Table A.4: different base points for the borderline (β = 2/3, ≤ 2 via points, re-use)", true),
    ] {
        let rs: Vec<&Row> = rows.iter().filter(|r| r.table == table).collect();
        if rs.is_empty() {
            continue;
        }
        let _ = writeln!(out, "\n### {title}\n");
        let first = if table == "A.4" { "location of base point" } else { "β" };
        let _ = write!(out, "| {first} | via points | solved |");
        if depth_cols {
            let _ = write!(out, " depth max (seed) | depth mean (seed) |");
        }
        let _ = writeln!(out, " calls max (seed) | calls mean (seed) | calls mean, solved | CPU s |");
        let cols = if depth_cols { 9 } else { 7 };
        let _ = writeln!(out, "|{}", "---|".repeat(cols));
        for r in rs {
            let m = &r.measured;
            let _ = write!(out, "| {} | {} | {}/{} |", r.label, r.via, m.solved, m.problems);
            if depth_cols {
                let _ = write!(
                    out,
                    " {} ({}) | {:.3} ({}) |",
                    m.depth_max,
                    opt(r.published.depth_max, 0),
                    m.depth_mean,
                    opt(r.published.depth_mean, 3)
                );
            }
            let _ = writeln!(
                out,
                " {} ({}) | {:.1} ({}) | {:.1} | {:.2} |",
                m.calls_max,
                opt(r.published.calls_max, 0),
                m.calls_mean,
                opt(r.published.calls_mean, 1),
                m.calls_mean_solved,
                m.seconds
            );
        }
    }
    out
}

/// The rows as CSV, one line per row, our numbers and the seed's.
pub fn csv(rows: &[Row]) -> String {
    let mut out = String::from(
        "table,label,via,problems,solved,depth_max,depth_mean,calls_max,calls_mean,calls_mean_solved,seconds,seed_depth_max,seed_depth_mean,seed_calls_max,seed_calls_mean,spec\n",
    );
    let o = |v: Option<f64>| v.map(|x| x.to_string()).unwrap_or_default();
    for r in rows {
        let m = &r.measured;
        let _ = writeln!(
            out,
            "{},\"{}\",{},{},{},{},{:.4},{},{:.3},{:.3},{:.3},{},{},{},{},\"{}\"",
            r.table,
            r.label,
            if r.via.starts_with("all") { "all" } else { "2" },
            m.problems,
            m.solved,
            m.depth_max,
            m.depth_mean,
            m.calls_max,
            m.calls_mean,
            m.calls_mean_solved,
            m.seconds,
            o(r.published.depth_max),
            o(r.published.depth_mean),
            o(r.published.calls_max),
            o(r.published.calls_mean),
            r.spec
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_cover_the_four_tables() {
        let r = rows(Budgets::default());
        assert_eq!(r.iter().filter(|r| r.table == "A.1").count(), 10);
        assert_eq!(r.iter().filter(|r| r.table == "A.2").count(), 6);
        assert_eq!(r.iter().filter(|r| r.table == "A.3").count(), 12);
        assert_eq!(r.iter().filter(|r| r.table == "A.4").count(), 8);
    }

    #[test]
    fn a_small_run_fills_the_tables() {
        let mut r = rows(Budgets::default());
        r.retain(|r| r.table == "A.2");
        run_rows(&mut r, 20, 1, super::super::discs::SEED_RADIUS, &|| {}).unwrap();
        for row in &r {
            assert_eq!(row.measured.problems, 20);
            assert!(
                row.measured.solved >= 18,
                "{}: {:?}",
                row.spec,
                row.measured
            );
            assert!(row.measured.calls_mean >= 1.0);
        }
        let md = markdown(&r);
        assert!(md.contains("Table A.2") && md.contains("| 2/3 |"));
        assert_eq!(csv(&r).lines().count(), 7);
    }
}
