//! The progress bar of long commands (indicatif; drawn only on a terminal).

use indicatif::{ProgressBar, ProgressStyle};

/// A bar over the samples of a run.
pub struct Bar {
    bar: ProgressBar,
}

impl Bar {
    pub fn samples() -> Self {
        let bar = ProgressBar::new(0);
        bar.set_style(
            ProgressStyle::with_template("{bar:40} {pos}/{len} samples {msg}")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        Bar { bar }
    }
}

impl sim::Progress for Bar {
    /// A new bar for every stretch of samples (a run of repeats starts several).
    fn start(&mut self, total: usize, done: usize) {
        *self = Bar::samples();
        self.bar.set_length(total as u64);
        self.bar.set_position(done as u64);
    }

    fn sample(&mut self, done: usize, note: &str) {
        self.bar.set_position(done as u64);
        self.bar.set_message(note.to_string());
    }

    fn finish(&mut self) {
        self.bar.finish_and_clear();
    }
}

/// A bar over the steps of a command (e.g. the items of `haff reproduce all`), with lines
/// printed above it.
pub struct Steps {
    bar: ProgressBar,
}

impl Steps {
    pub fn new(total: usize, unit: &str) -> Self {
        let bar = ProgressBar::new(total as u64);
        bar.set_style(
            ProgressStyle::with_template(&format!("{{bar:40}} {{pos}}/{{len}} {unit} {{msg}}"))
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        Steps { bar }
    }

    /// What is being done now.
    pub fn message(&mut self, text: &str) {
        self.bar.set_message(text.to_string());
    }

    /// One step done.
    pub fn step(&mut self) {
        self.bar.inc(1);
    }

    /// A line on stdout above the bar.
    pub fn println(&mut self, line: &str) {
        self.bar.suspend(|| println!("{line}"));
    }

    pub fn finish(&mut self) {
        self.bar.finish_and_clear();
    }
}
