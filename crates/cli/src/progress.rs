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
