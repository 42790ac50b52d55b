//! Converts one model with `convert_all` and prints every step's time per method as it
//! finishes, each method's result the moment it ends, and the time to the first and the last
//! plan: where a slow model spends its time (docs/performance.md).
//!
//! `cargo run --release -p platener --example step_times -- MODEL [METHOD…] [--timeout S] [-t MM]`

use std::sync::Arc;
use std::time::{Duration, Instant};

use platener::convert::{Event, Request, convert_all};
use platener::method::MethodKind;
use platener::pipeline::StepEvent;
use platener::{Cancel, Settings, Source};

fn main() -> Result<(), String> {
    let mut args = std::env::args().skip(1);
    let model = args
        .next()
        .ok_or("usage: step_times MODEL [METHOD…] [--timeout S] [-t MM]")?;
    let (mut methods, mut timeout) = (Vec::new(), Some(Duration::from_secs(60)));
    let mut settings = Settings::default();
    while let Some(a) = args.next() {
        if a == "-t" {
            let t: f64 = args.next().and_then(|s| s.parse().ok()).ok_or("-t MM")?;
            settings.thicknesses = vec![t];
        } else if a == "--timeout" {
            let s: f64 = args.next().and_then(|s| s.parse().ok()).ok_or("--timeout S")?;
            timeout = (s > 0.0).then(|| Duration::from_secs_f64(s));
        } else {
            methods.push(a.parse::<MethodKind>().map_err(|e| e.to_string())?);
        }
    }
    if methods.is_empty() {
        methods = MethodKind::ALL.to_vec();
    }
    let start = Instant::now();
    let progress = Arc::new(move |e: Event<'_>| match e {
        Event::Step {
            method,
            event: StepEvent::Finished(r),
        } => println!(
            "{:>8.3} s  {:<10} {:<9} {:>9.1} ms  {} warnings",
            start.elapsed().as_secs_f64(),
            method.map_or("shared", MethodKind::name),
            r.name,
            r.millis,
            r.warnings.len()
        ),
        Event::Step { .. } | Event::Shared(_) => {}
        Event::Method(m) => println!(
            "{:>8.3} s  {:<10} {:?} in {:.3} s, score {:?}{}",
            start.elapsed().as_secs_f64(),
            m.method.name(),
            m.status,
            m.seconds,
            m.score.as_ref().map(|s| s.total),
            m.error.as_ref().map(|e| format!(": {e}")).unwrap_or_default()
        ),
    });
    let request = Request {
        methods,
        timeout,
        ..Request::new(Source::File(model.into()), settings)
    };
    let all = convert_all(request, &Cancel::default(), progress);
    println!("best {:?}, {:.3} s", all.best.map(MethodKind::name), all.seconds);
    Ok(())
}
