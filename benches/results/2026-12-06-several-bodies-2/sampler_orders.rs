// The orders of the bodies sampler's free samples on the swaps in a corridor (README.md of this
// folder). Not built with the crate: copy it to examples/ and run
// `cargo run --release --example sampler_orders` from the repository root.
use rand::SeedableRng;
use viaroad::oracle::CallCounts;
use viaroad::roadmap::Sampler;
use viaroad::scene::Scene;
fn main() {
    for k in [2usize, 3, 4, 6] {
        let scene = Scene::load(std::path::Path::new(&format!(
            "scenes/bodies/swap-corridor-{k}.toml"
        )))
        .unwrap();
        let oracle = scene.oracle();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
        let mut counts = CallCounts::default();
        let (mut n, mut fail, mut start_order, mut goal_order, mut niche_last, mut niche_any) =
            (0, 0, 0, 0, 0, 0);
        let niche = k as f64 - 0.5;
        let t = std::time::Instant::now();
        for _ in 0..20000 {
            match Sampler::Bodies
                .sample(&scene.space, &*oracle, 1, &mut rng, &mut counts)
                .unwrap()
            {
                None => fail += 1,
                Some(q) => {
                    n += 1;
                    let inn = |i: usize| q[3 * i + 1] > 0.95 && (q[3 * i] - niche).abs() < 0.2;
                    let mut low: Vec<(f64, usize)> =
                        (0..k).filter(|&i| !inn(i)).map(|i| (q[3 * i], i)).collect();
                    low.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap());
                    let order: Vec<usize> = low.iter().map(|p| p.1).collect();
                    let any = (0..k).any(inn);
                    if any {
                        niche_any += 1;
                    }
                    if inn(k - 1) {
                        niche_last += 1;
                    }
                    if order == (0..k).collect::<Vec<_>>() {
                        start_order += 1;
                    }
                    let mut g = vec![k - 1];
                    g.extend(0..k - 1);
                    if order == g {
                        goal_order += 1;
                    }
                    if inn(k - 1) && order == (0..k - 1).collect::<Vec<_>>() {
                        println!("  k={k}: last in niche, others in order");
                    }
                }
            }
        }
        println!("k={k}: 20000 attempts, {n} free, {fail} stuck, {} state checks, {:.2} s; start order {start_order}, goal order {goal_order}, a body in the niche {niche_any}, the last body in the niche {niche_last}", counts.state_checks, t.elapsed().as_secs_f64());
    }
}
