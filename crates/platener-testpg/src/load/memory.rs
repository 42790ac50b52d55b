//! The server's memory while the load runs: resident memory of a process and all its
//! descendants (`platener serve` and its worker processes), read from /proc.

use std::collections::{BTreeMap, BTreeSet};
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Duration;

/// How often the sampler reads /proc.
const SAMPLE_EVERY: Duration = Duration::from_millis(100);

/// Resident memory (kB) of `root` and its descendants, `None` when `root` does not exist.
pub fn tree_rss_kb(root: u32) -> Option<u64> {
    tree_rss(root).map(|(own, descendants)| own + descendants)
}

/// Resident memory (kB) of `root` alone and of its descendants together.
fn tree_rss(root: u32) -> Option<(u64, u64)> {
    let mut children: BTreeMap<u32, Vec<u32>> = BTreeMap::new();
    for entry in std::fs::read_dir("/proc").ok()?.flatten() {
        let Some(pid) = entry.file_name().to_str().and_then(|s| s.parse::<u32>().ok()) else {
            continue;
        };
        if let Some(ppid) = parent_of(pid) {
            children.entry(ppid).or_default().push(pid);
        }
    }
    let mut tree = BTreeSet::new();
    let mut todo = vec![root];
    while let Some(pid) = todo.pop() {
        if tree.insert(pid) {
            todo.extend(children.get(&pid).into_iter().flatten());
        }
    }
    let root_rss = rss_kb(root)?;
    let descendants = tree
        .iter()
        .filter(|&&p| p != root)
        .filter_map(|&p| rss_kb(p))
        .sum::<u64>();
    Some((root_rss, descendants))
}

/// The parent pid, from `/proc/PID/stat` (the field after the state, after the last `)`).
fn parent_of(pid: u32) -> Option<u32> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    stat.rsplit_once(')')?.1.split_whitespace().nth(1)?.parse().ok()
}

/// `VmRSS` of one process in kB (absent for kernel threads and zombies).
fn rss_kb(pid: u32) -> Option<u64> {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    let line = status.lines().find(|l| l.starts_with("VmRSS:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// Peak resident memory of a process tree, MB: the whole tree, the root alone and its
/// descendants together (each peak taken on its own, so the tree's may be less than the sum).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Peaks {
    /// The root and its descendants.
    pub tree_mb: f64,
    /// The root process (the server).
    pub root_mb: f64,
    /// Its descendants (the workers).
    pub descendants_mb: f64,
}

/// Peaks in kB: tree, root, descendants.
#[derive(Debug, Default)]
struct PeakKb([AtomicU64; 3]);

impl PeakKb {
    fn record(&self, (own, descendants): (u64, u64)) {
        for (peak, kb) in self.0.iter().zip([own + descendants, own, descendants]) {
            peak.fetch_max(kb, Ordering::Relaxed);
        }
    }

    fn mb(&self, i: usize) -> f64 {
        super::stats::round3(self.0[i].load(Ordering::Relaxed) as f64 / 1024.0)
    }
}

/// Samples [`tree_rss_kb`] (root and descendants apart) in the background until
/// [`Sampler::finish`].
#[derive(Debug)]
pub(crate) struct Sampler {
    peak: Arc<PeakKb>,
    task: tokio::task::JoinHandle<()>,
    pid: u32,
}

impl Sampler {
    /// Starts sampling `pid`'s tree.
    pub(crate) fn start(pid: u32) -> Sampler {
        let peak = Arc::new(PeakKb::default());
        peak.record(tree_rss(pid).unwrap_or_default());
        let shared = Arc::clone(&peak);
        let task = tokio::spawn(async move {
            let mut tick = tokio::time::interval(SAMPLE_EVERY);
            loop {
                tick.tick().await;
                if let Some(kb) = tokio::task::spawn_blocking(move || tree_rss(pid)).await.ok().flatten() {
                    shared.record(kb);
                }
            }
        });
        Sampler { peak, task, pid }
    }

    /// Stops sampling; the peaks (one last sample included).
    pub(crate) fn finish(self) -> Peaks {
        self.task.abort();
        self.peak.record(tree_rss(self.pid).unwrap_or_default());
        Peaks {
            tree_mb: self.peak.mb(0),
            root_mb: self.peak.mb(1),
            descendants_mb: self.peak.mb(2),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_process_tree_counts_its_descendants() {
        let own = tree_rss_kb(std::process::id()).expect("this process exists");
        assert!(own > 1000, "a test process holds more than 1 MB, got {own} kB");
        assert_eq!(tree_rss_kb(u32::MAX), None);
        // A shell waiting for its child `sleep`: the tree is the shell plus the sleep.
        let mut shell = std::process::Command::new("sh")
            .args(["-c", "sleep 30 & wait"])
            .spawn()
            .expect("sh");
        let pid = shell.id();
        let mut measured = None;
        for _ in 0..500 {
            let kids: Vec<u32> = std::fs::read_dir("/proc")
                .expect("proc")
                .flatten()
                .filter_map(|e| e.file_name().to_str()?.parse::<u32>().ok())
                .filter(|&p| parent_of(p) == Some(pid) && rss_kb(p).is_some_and(|kb| kb > 0))
                .collect();
            // Sizes change while `sleep` is being loaded: measure when they hold still
            // across the tree's reading.
            if let [kid] = kids[..] {
                let before = (rss_kb(pid), rss_kb(kid));
                let tree = tree_rss(pid);
                if before == (rss_kb(pid), rss_kb(kid)) {
                    measured = Some((kid, before.0, before.1, tree));
                    break;
                }
            }
            std::thread::sleep(Duration::from_millis(10));
        }
        if let Some((kid, ..)) = measured {
            let _ = std::process::Command::new("kill").arg(kid.to_string()).status();
        }
        let _ = shell.kill();
        let _ = shell.wait();
        let (_, Some(sh), Some(kid), Some(tree)) = measured.expect("the shell started its sleep") else {
            panic!("both processes have a resident size: {measured:?}");
        };
        assert_eq!(tree, (sh, kid), "the shell {sh} kB apart from its sleep {kid} kB");
    }
}
