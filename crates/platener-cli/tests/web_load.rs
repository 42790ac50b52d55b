//! The load benchmark, bounded: 20 clients against the real `platener serve` on SQLite
//! (`platener-load bench`'s code path, issue 17). Every request must succeed and every
//! conversion end done with a whole plan ZIP; nothing asserts on speed.

use std::time::Duration;

use platener_testpg::load::Config;
use platener_testpg::load::bench::{BenchConfig, Database, bench};

const EXAMPLE_BOX: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/box-3mm.stl");

#[test]
fn twenty_clients_on_sqlite_all_done_with_no_failed_request() {
    let model = std::fs::read(EXAMPLE_BOX).expect("the example box");
    let config = BenchConfig {
        platener: env!("CARGO_BIN_EXE_platener").into(),
        databases: vec![Database::Sqlite],
        clients: vec![20],
        workers: 2,
        client: Config {
            base_url: String::new(),
            clients: 0,
            conversions_per_client: 1,
            model,
            model_name: "box-3mm.stl".into(),
            status_interval: Duration::from_millis(100),
            status_reads_while_streaming: 5,
            // Bounds a hang; a conversion of the box takes well under a second.
            timeout: Duration::from_secs(300),
            server_pid: None,
        },
    };
    let runs = bench(&config, |_| {}).expect("the benchmark runs");
    let [run] = &runs[..] else { panic!("one run: {runs:?}") };
    let s = &run.summary;
    assert_eq!(s.requests.failed, 0, "{:?}", s.errors);
    assert_eq!(
        (s.conversions.submitted, s.conversions.done, s.conversions.failed),
        (20, 20, 0)
    );
    // Every client uploaded, streamed to `done`, read its status and downloaded a ZIP whose
    // directory lists plan.json (the client checks it).
    assert_eq!((s.uploads.count, s.downloads.count, s.conversion.count), (20, 20, 20));
    assert!(s.status_reads.count >= 40, "{:?}", s.status_reads);
    assert!(s.plan_bytes > 20 * 1000, "{}", s.plan_bytes);
    assert!(s.workers_peak_rss_mb.is_some_and(|mb| mb > 1.0), "{s:?}");
}
