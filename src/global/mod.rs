//! Global methods beside the roadmap, from the project's other seeds: Brooks's freeways
//! ([`cones`], `seeds/001_…`). They work on the same planar scenes and queries as the
//! roadmap, so that a user can compare them (`viaroad solve SCENE --global cones`), and can
//! start a roadmap ([`seeding`]: `build --seed-from cones`, `bench local --seed-from plain cones`).

pub mod cones;
pub mod seeding;

pub use seeding::{Seeded, Seeding, UnknownSeeding};
