//! The `viaroad` command line: build roadmaps, answer queries, run the seed's experiments and
//! benchmarks, draw pictures. Errors are reported in one line with a non-zero exit code.

mod cli;

use clap::Parser;

/// Lets a closed stdout pipe end the program quietly, as Unix tools do (`viaroad solve … |
/// head -1`): Rust ignores SIGPIPE, so every later `println!` would panic with "Broken pipe";
/// with the default action the process ends at the first write to the closed pipe, wherever
/// that write is. `bench local`, which writes to its children's pipes, ignores it
/// again for itself. SIGXFSZ is ignored, so that a file size limit is a write error.
fn set_signal_dispositions() {
    #[cfg(unix)]
    // SAFETY: setting a signal's disposition to the default, before any thread is started.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
        // a file size limit (`ulimit -f`) then fails the write with EFBIG, which a save
        // reports in one line, keeping the previous roadmap, instead of killing the process
        // with its temporary file left behind
        libc::signal(libc::SIGXFSZ, libc::SIG_IGN);
    }
}

fn main() {
    set_signal_dispositions();
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
