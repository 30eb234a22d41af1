// temporary measurement: how many oracle questions repeat within one connect and within one problem
use std::collections::HashMap;
use std::sync::Mutex;
use viaroad::bench::discs::{problem, DiscProblem, GOAL, SEED_RADIUS, START};
use viaroad::bench::tables::{rows, Budgets};
use viaroad::interval::IntervalList;
use viaroad::local::viapoint::ViaPoint;
use viaroad::local::LocalMethod;
use viaroad::oracle::{CallCounts, CollisionOracle, OracleError, Workspace};
use viaroad::space::{Change, Motion};

struct Rec<'a, O> {
    inner: &'a O,
    seen: Mutex<(HashMap<Vec<u64>, u32>, u64, u64)>,
}
fn key(m: &Motion) -> Vec<u64> {
    let mut k: Vec<u64> = m.origin.iter().map(|x| x.to_bits()).collect();
    if let Change::Linear(d) = &m.change {
        k.extend(d.iter().map(|x| x.to_bits()));
    }
    k.push(m.range.lo.to_bits());
    k.push(m.range.hi.to_bits());
    k.push(m.sweep as u64);
    k
}
impl<'a, O: CollisionOracle> CollisionOracle for Rec<'a, O> {
    fn intervals(&self, m: &Motion, c: &mut CallCounts) -> Result<IntervalList, OracleError> {
        let mut o = IntervalList::new();
        self.intervals_into(m, &mut o, &mut Workspace::new(), c)?;
        Ok(o)
    }
    fn intervals_into(
        &self,
        m: &Motion,
        out: &mut IntervalList,
        ws: &mut Workspace,
        c: &mut CallCounts,
    ) -> Result<(), OracleError> {
        let mut s = self.seen.lock().unwrap();
        s.1 += 1;
        let e = s.0.entry(key(m)).or_insert(0);
        let rep = *e > 0;
        *e += 1;
        if rep {
            s.2 += 1;
        }
        drop(s);
        self.inner.intervals_into(m, out, ws, c)
    }
    fn collides(&self, q: &[f64], c: &mut CallCounts) -> bool {
        self.inner.collides(q, c)
    }
    fn prefers_unclipped(&self) -> bool {
        self.inner.prefers_unclipped()
    }
}

fn main() {
    let n: u64 = std::env::args()
        .nth(1)
        .map(|s| s.parse().unwrap())
        .unwrap_or(100);
    let space = DiscProblem::space();
    let rs = rows(Budgets::default());
    let (mut tot, mut dup_conn, mut dup_prob) = (0u64, 0u64, 0u64);
    let mut per_row = vec![(0u64, 0u64); rs.len()];
    for i in 0..n {
        let o = problem(1, i, SEED_RADIUS).oracle();
        let prob = Rec {
            inner: &o,
            seen: Mutex::new((HashMap::new(), 0, 0)),
        };
        for (ri, r) in rs.iter().enumerate() {
            let conn = Rec {
                inner: &prob,
                seen: Mutex::new((HashMap::new(), 0, 0)),
            };
            let m = ViaPoint::new(r.options.clone());
            m.connect(&space, &conn, &START, &GOAL).unwrap();
            let s = conn.seen.lock().unwrap();
            tot += s.1;
            dup_conn += s.2;
            per_row[ri].0 += s.1;
            per_row[ri].1 += s.2;
        }
        dup_prob += prob.seen.lock().unwrap().2;
    }
    println!("calls {tot}  repeats within a connect {dup_conn} ({:.1}%)  repeats within a problem (all rows) {dup_prob} ({:.1}%)", 100.0*dup_conn as f64/tot as f64, 100.0*dup_prob as f64/tot as f64);
    for (r, (t, d)) in rs.iter().zip(per_row) {
        println!(
            "{} {:>6} {:>5}: calls {t:>9} repeats {d:>9} ({:.1}%)",
            r.table,
            r.label,
            r.via,
            100.0 * d as f64 / t.max(1) as f64
        );
    }
}
