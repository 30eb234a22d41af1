use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher, BuildHasher, Hash};
use std::time::Instant;

/// A multiply-and-fold hasher over 64-bit words (bytes are taken eight at a time).
#[derive(Default, Clone, Copy)]
pub struct MixHasher(u64);

impl Hasher for MixHasher {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        let mut chunks = bytes.chunks_exact(8);
        for c in &mut chunks {
            self.write_u64(u64::from_le_bytes(c.try_into().expect("chunks of eight")));
        }
        let rest = chunks.remainder();
        if !rest.is_empty() {
            let mut last = [0u8; 8];
            last[..rest.len()].copy_from_slice(rest);
            // the length tells "ab" from "ab\0"
            self.write_u64(u64::from_le_bytes(last) ^ ((rest.len() as u64) << 59));
        }
    }

    fn write_u64(&mut self, x: u64) {
        let h = (self.0 ^ x).wrapping_mul(0x9e37_79b9_7f4a_7c15);
        self.0 = h ^ (h >> 32);
    }

    fn write_u32(&mut self, x: u32) {
        self.write_u64(u64::from(x));
    }

    fn write_usize(&mut self, x: usize) {
        self.write_u64(x as u64);
    }
}


type Mix = BuildHasherDefault<MixHasher>;
type Fx = rustc_hash::FxBuildHasher;

/// Keys as the library makes them: welded vertex coordinates' bits, a move's bits, id pairs.
fn keys() -> (Vec<[u64; 3]>, Vec<Vec<u64>>, Vec<(u32, u32)>) {
    let mut weld = Vec::new();
    for i in 0..60 { for j in 0..60 { for k in 0..60 {
        let p = [i as f64 * 0.013 - 0.4, j as f64 * 0.021 + 0.1, k as f64 * 0.007];
        weld.push(p.map(|c: f64| (c + 0.0).to_bits()));
    }}}
    let mut moves = Vec::new();
    let mut x = 0x1234_5678_9abc_def0u64;
    for _ in 0..100_000 {
        let q: Vec<u64> = (0..7).map(|_| { x ^= x << 13; x ^= x >> 7; x ^= x << 17; ((x % 6283) as f64 * 1e-3 - 3.1).to_bits() }).collect();
        moves.push(q);
    }
    let pairs: Vec<(u32, u32)> = (0..200_000u32).map(|i| (i % 977, i / 977)).collect();
    (weld, moves, pairs)
}

fn run<S: BuildHasher + Default, K: Hash + Eq + Clone>(keys: &[K]) -> (f64, usize) {
    let t = Instant::now();
    let mut m: HashMap<K, usize, S> = HashMap::default();
    for (i, k) in keys.iter().enumerate() { m.entry(k.clone()).or_insert(i); }
    let mut hits = 0;
    for _ in 0..3 { for k in keys { hits += m.get(k).copied().unwrap_or(0) & 1; } }
    (t.elapsed().as_secs_f64() * 1e3, hits + m.len())
}

fn main() {
    let (weld, moves, pairs) = keys();
    for round in 0..5 {
        let a = run::<Mix, _>(&weld); let b = run::<Fx, _>(&weld);
        let c = run::<Mix, _>(&moves); let d = run::<Fx, _>(&moves);
        let e = run::<Mix, _>(&pairs); let f = run::<Fx, _>(&pairs);
        println!("round {round}: weld [u64;3] x{}: mix {:.1} ms fx {:.1} ms | move Vec<u64>(7) x{}: mix {:.1} fx {:.1} | (u32,u32) x{}: mix {:.1} fx {:.1}  ({} {} {} {} {} {})",
            weld.len(), a.0, b.0, moves.len(), c.0, d.0, pairs.len(), e.0, f.0, a.1, b.1, c.1, d.1, e.1, f.1);
    }
}
