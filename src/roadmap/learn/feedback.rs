//! Applying a connection attempt to the growing roadmap, with the local method's discoveries
//! fed back as nodes and edges (CHS §1.6).

use super::work::Work;
use crate::local::{Connection, Outcome};

impl Work<'_> {
    /// Records an attempt from node `a` to node `z` and keeps what it found.
    pub(super) fn apply(&mut self, a: u32, z: u32, c: &Connection) {
        self.counts += c.counts;
        self.attempts += 1;
        let ok = c.is_connected();
        self.connected += u64::from(ok);
        // an attempt the learning deadline stopped says nothing about how hard its ends are
        // (one its own time cap stopped failed like one that ran out of calls)
        if !(c.outcome == Outcome::Interrupted && self.stopped) {
            for n in [a, z] {
                self.tries[n as usize] += 1;
                self.failures[n as usize] += u32::from(!ok);
            }
        }
        if self.feedback {
            // a discovered configuration becomes a node when a certified free segment joins it
            // to something: via points the search made but never connected stay out
            let configs = &c.discoveries.configs;
            let mut ids: Vec<Option<u32>> = vec![None; configs.len()];
            if let Some(first) = ids.first_mut() {
                *first = Some(a);
            }
            if let Some(second) = ids.get_mut(1) {
                *second = Some(z);
            }
            for &(i, j) in &c.discoveries.free_segments {
                let (i, j) = (i as usize, j as usize);
                if i >= configs.len() || j >= configs.len() {
                    continue;
                }
                let x = *ids[i].get_or_insert_with(|| self.add_node(&configs[i]));
                let y = *ids[j].get_or_insert_with(|| self.add_node(&configs[j]));
                self.add_edge(x, y, &[]);
            }
            if ok && c.path.len() >= 2 {
                // the path itself, in case the method did not list all its segments
                let mut prev = a;
                for (k, q) in c.path.iter().enumerate().skip(1) {
                    let id = if k + 1 == c.path.len() {
                        z
                    } else {
                        self.add_node(q)
                    };
                    self.add_edge(prev, id, &[]);
                    prev = id;
                }
            }
        } else if ok && (self.cycle_edges || !self.uf.equiv(a, z)) {
            let interior = if c.path.len() >= 2 {
                &c.path[1..c.path.len() - 1]
            } else {
                &[]
            };
            self.add_edge(a, z, interior);
        }
    }
}
