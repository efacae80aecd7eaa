//! Progress of long work: a bar on a terminal, a line at the start and the
//! end otherwise (indicatif hides bars when stderr is not a terminal).

use std::io::IsTerminal;
use std::time::Instant;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// The progress of `len` steps of `unit` (e.g. "lines"), with `message`;
/// hidden entirely when `quiet` (JSON output).
pub(crate) struct Progress {
    bar: ProgressBar,
    message: String,
    start: Instant,
    lines: bool,
}

impl Progress {
    pub(crate) fn new(len: usize, unit: &str, message: impl Into<String>, quiet: bool) -> Progress {
        let message = message.into();
        let bar = ProgressBar::new(len as u64);
        let template = format!("{{msg}} [{{bar:40}}] {{pos}}/{{len}} {unit}, {{eta}} left");
        bar.set_style(ProgressStyle::with_template(&template).unwrap_or_else(|_| ProgressStyle::default_bar()));
        bar.set_message(message.clone());
        let terminal = std::io::stderr().is_terminal();
        if quiet || !terminal {
            bar.set_draw_target(ProgressDrawTarget::hidden());
        }
        let lines = !quiet && !terminal;
        if lines {
            eprintln!("{message}: {len} {unit}...");
        }
        Progress { bar, message, start: Instant::now(), lines }
    }

    /// A step of work of unknown length (a build): a spinner on a terminal.
    pub(crate) fn spinner(message: impl Into<String>, quiet: bool) -> Progress {
        let message = message.into();
        let bar = ProgressBar::new_spinner();
        bar.set_message(message.clone());
        let terminal = std::io::stderr().is_terminal();
        if quiet || !terminal {
            bar.set_draw_target(ProgressDrawTarget::hidden());
        } else {
            bar.enable_steady_tick(std::time::Duration::from_millis(200));
        }
        let lines = !quiet && !terminal;
        if lines {
            eprintln!("{message}...");
        }
        Progress { bar, message, start: Instant::now(), lines }
    }

    pub(crate) fn set(&self, done: usize) {
        self.bar.set_position(done as u64);
    }

    /// A new phase of the work: the spinner's message, or a line of its own.
    pub(crate) fn phase(&self, phase: &str) {
        self.bar.set_message(format!("{}: {phase}", self.message));
        if self.lines {
            eprintln!("{}: {phase}", self.message);
        }
    }

    pub(crate) fn inc(&self) {
        self.bar.inc(1);
    }

    /// Prints `f`'s output without tearing the bar.
    pub(crate) fn suspend<R>(&self, f: impl FnOnce() -> R) -> R {
        self.bar.suspend(f)
    }

    pub(crate) fn finish(self) {
        self.bar.finish_and_clear();
        if self.lines {
            eprintln!("{}: done in {:.1} s", self.message, self.start.elapsed().as_secs_f64());
        }
    }
}
