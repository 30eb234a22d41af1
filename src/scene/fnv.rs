//! The scenes' fingerprint hash.

use crate::geometry::{Polygon, TriMesh};

/// FNV-1a, 64 bit: stable across platforms and versions (unlike `std`'s hasher).
pub(super) struct Fnv(u64);

impl Fnv {
    pub(super) fn new() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
    pub(super) fn bytes(&mut self, b: &[u8]) {
        for &x in b {
            self.0 ^= x as u64;
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    pub(super) fn str(&mut self, s: &str) {
        self.bytes(&(s.len() as u64).to_le_bytes());
        self.bytes(s.as_bytes());
    }
    pub(super) fn floats(&mut self, v: &[f64]) {
        self.bytes(&(v.len() as u64).to_le_bytes());
        v.iter()
            .for_each(|x| self.bytes(&x.to_bits().to_le_bytes()));
    }
    pub(super) fn polygon(&mut self, p: &Polygon) {
        let v: Vec<f64> = p.vertices.iter().flat_map(|v| [v.x, v.y]).collect();
        self.floats(&v);
    }
    pub(super) fn mesh(&mut self, m: &TriMesh) {
        let v: Vec<f64> = m.vertices.iter().flat_map(|v| [v.x, v.y, v.z]).collect();
        self.floats(&v);
        self.bytes(&(m.triangles.len() as u64).to_le_bytes());
        m.triangles
            .iter()
            .flatten()
            .for_each(|i| self.bytes(&i.to_le_bytes()));
    }
    pub(super) fn finish(&self) -> u64 {
        self.0
    }
}
