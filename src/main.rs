//! The `viaroad` command line: build roadmaps, answer queries, run the seed's experiments and
//! benchmarks, draw pictures. Errors are reported in one line with a non-zero exit code.

mod cli;

use clap::Parser;

fn main() {
    let args = cli::Cli::parse();
    if let Err(e) = cli::run(args) {
        // one line: the error and those of its causes that its message does not already say
        let mut line = String::new();
        for cause in e.chain().map(|c| c.to_string()) {
            if !line.contains(&cause) {
                if !line.is_empty() {
                    line.push_str(": ");
                }
                line.push_str(&cause);
            }
        }
        eprintln!("error: {line}");
        std::process::exit(1);
    }
}
