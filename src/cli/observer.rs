//! The command line's observer: what `hertz run` and `hertz check` show on stderr while they
//! work. Normal: a line per finished step, warnings and cut-backs, and on a terminal a progress
//! bar with the running iteration or phase; in a log (not a terminal) a line about a phase that
//! has gone on for a while, so a long factorization never leaves the log silent. `-v`: a line
//! per Newton iteration, the solver's details, each factorization with its size and each step's
//! phase times. `-q`: nothing.

use hertz::output::number::sci;
use hertz::solve::{IterationReport, Observer, Phase, StepReport};
use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// How much the command line shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Level {
    Quiet,
    Normal,
    Verbose,
}

/// In a log, a phase still going after this long gets a line, and another every `REPEAT`.
const FIRST_NOTE: Duration = Duration::from_secs(10);
const REPEAT: Duration = Duration::from_secs(60);

/// The phase under way and when output last appeared (shared with the log's watch thread).
struct Now {
    phase: String,
    since: Instant,
    last_output: Instant,
}

pub struct CliObserver {
    level: Level,
    bar: Option<indicatif::ProgressBar>,
    now: Arc<Mutex<Now>>,
    stop: Arc<AtomicBool>,
    watch: Option<std::thread::JoinHandle<()>>,
}

impl CliObserver {
    /// The observer at `level` (the progress bar learns the number of steps at the set-up).
    pub fn new(level: Level) -> CliObserver {
        let terminal = std::io::stderr().is_terminal();
        let bar = (level == Level::Normal && terminal).then(|| {
            let bar = indicatif::ProgressBar::new(0);
            bar.set_style(
                indicatif::ProgressStyle::with_template(
                    "[{elapsed_precise}] {bar:30} step {pos}/{len}  {msg}",
                )
                .expect("valid progress template"),
            );
            bar.enable_steady_tick(Duration::from_millis(250));
            bar
        });
        let now = Arc::new(Mutex::new(Now {
            phase: String::new(),
            since: Instant::now(),
            last_output: Instant::now(),
        }));
        let stop = Arc::new(AtomicBool::new(false));
        let watch = (level != Level::Quiet && !terminal).then(|| {
            let (now, stop) = (now.clone(), stop.clone());
            std::thread::spawn(move || watch_log(&now, &stop))
        });
        CliObserver {
            level,
            bar,
            now,
            stop,
            watch,
        }
    }

    /// A line on stderr, above the bar if there is one.
    fn line(&self, text: &str) {
        match &self.bar {
            Some(bar) => bar.println(text),
            None => eprintln!("{text}"),
        }
        self.now.lock().expect("not poisoned").last_output = Instant::now();
    }
}

/// In a log: a line about a phase that has gone on for `FIRST_NOTE` with no other output, then
/// every `REPEAT`.
fn watch_log(now: &Mutex<Now>, stop: &AtomicBool) {
    while !stop.load(Ordering::Relaxed) {
        std::thread::sleep(Duration::from_millis(200));
        let mut n = now.lock().expect("not poisoned");
        let quiet_for = n.last_output.elapsed();
        let wait = if n.last_output > n.since {
            REPEAT
        } else {
            FIRST_NOTE
        };
        if !n.phase.is_empty() && quiet_for >= wait && n.since.elapsed() >= FIRST_NOTE {
            eprintln!(
                "    … {} for {:.0} s",
                n.phase,
                n.since.elapsed().as_secs_f64()
            );
            n.last_output = Instant::now();
        }
    }
}

impl Drop for CliObserver {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(w) = self.watch.take() {
            let _ = w.join();
        }
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}

impl Observer for CliObserver {
    fn phase(&self, phase: &Phase) {
        {
            let mut n = self.now.lock().expect("not poisoned");
            n.phase = phase.to_string();
            n.since = Instant::now();
        }
        if let Some(bar) = &self.bar {
            if let Phase::SetUp { steps, .. } = phase {
                bar.set_length(*steps as u64);
            }
            if !matches!(phase, Phase::Assembly | Phase::Solve) {
                bar.set_message(phase.to_string());
            }
        }
        if self.level == Level::Verbose
            && matches!(phase, Phase::SetUp { .. } | Phase::Factorization { .. })
        {
            self.line(&format!("      {phase}"));
        }
    }

    fn iteration(&self, r: &IterationReport) {
        if let Some(bar) = &self.bar {
            bar.set_message(format!(
                "iteration {:3}  residual {}",
                r.iteration,
                sci(r.residual, 2)
            ));
        }
        if self.level != Level::Verbose {
            return;
        }
        let list = |v: &[usize]| {
            let mut l: Vec<String> = v.iter().take(12).map(|n| n.to_string()).collect();
            if v.len() > 12 {
                l.push(format!("… ({} more)", v.len() - 12));
            }
            l.join(" ")
        };
        let mut line = format!(
            "    iteration {:3}  residual {}",
            r.iteration,
            sci(r.residual, 3)
        );
        if r.contact_points > 0 {
            line += &format!("  contact nodes closed {}/{}", r.closed, r.contact_points);
            if !r.closed_nodes.is_empty() {
                line += &format!("; closed nodes {}", list(&r.closed_nodes));
            }
            if !r.opened_nodes.is_empty() {
                line += &format!("; opened nodes {}", list(&r.opened_nodes));
            }
            if let Some(k) = r.slipping {
                line += &format!("; slipping {k}");
            }
            if !r.switched_nodes.is_empty() {
                line += &format!(" (stick/slip changed: nodes {})", list(&r.switched_nodes));
            }
        }
        self.line(&line);
    }

    fn step(&self, r: &StepReport) {
        if self.level == Level::Quiet {
            return;
        }
        self.line(&format!(
            "step {}/{}  t = {}  iterations {}  residual {}  substeps {}  {:.3} s",
            r.step,
            r.n_steps,
            sci(r.time, 4),
            r.iterations,
            sci(r.residual, 2),
            r.substeps,
            r.wall_seconds
        ));
        if let Some(bar) = &self.bar {
            bar.inc(1);
        }
        if self.level == Level::Verbose {
            let t = &r.times;
            self.line(&format!(
                "    time: contact search {:.3} s, contact points {:.3} s, assembly {:.3} s, \
                 factorization {:.3} s, solves {:.3} s{}",
                t.search,
                t.contact,
                t.assembly,
                t.factor,
                t.solve,
                match r.krylov_iterations {
                    0 => String::new(),
                    k => format!(" (last solve: {k} Krylov iterations)"),
                }
            ));
        }
    }

    fn retry(&self, message: &str) {
        if self.level != Level::Quiet {
            self.line(message);
        }
    }

    fn detail(&self, message: &str) {
        if self.level == Level::Verbose {
            self.line(&format!("      {message}"));
        }
    }

    fn warning(&self, message: &str) {
        if self.level != Level::Quiet {
            self.line(&format!("warning: {message}"));
        }
    }
}
