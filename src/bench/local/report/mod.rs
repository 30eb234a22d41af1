//! Summaries of a local-method benchmark: per scene × method over the runs, rankings by time
//! and by nodes to 99 % of the queries, what feedback is worth; Markdown, CSV and JSON.
//!
//! | file | idea |
//! |---|---|
//! | `aggregate` | the numbers: statistics over runs, the solvable set, summaries, rankings |
//! | `markdown` | the summary printed on stdout |
//! | `csv` | one row per run, and the JSON of everything |

mod aggregate;
mod csv;
mod markdown;

pub use aggregate::{first_stage_solving, MethodSummary, Report, SceneInfo, SceneReport, Stats};
