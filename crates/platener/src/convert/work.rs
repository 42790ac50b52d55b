//! The conversion's own thread: shared steps once, then each method from a fork of the state,
//! each caught, scored and handed back over a channel while the caller's thread keeps time.

use std::sync::Arc;
use std::sync::mpsc::{self, RecvTimeoutError, Sender};
use std::time::{Duration, Instant};

use super::panic::catch;
use super::{Event, Fault, FaultKind, MethodResult, Progress, Request, Status};
use crate::assembly::analyse;
use crate::context::Cancel;
use crate::error::{Error, Internal, ModelProblem};
use crate::method::MethodKind;
use crate::pipeline::{self, FOUNDATION, State, StepEvent, StepId};
use crate::score::{self, Score};
use crate::verify::{self, Verification};

/// How long a cancelled conversion thread is waited for before it is left behind.
const CANCEL_GRACE: Duration = Duration::from_secs(2);
/// How often the caller's cancel handle is looked at while waiting.
const POLL: Duration = Duration::from_millis(50);
/// The steps every method runs with the same settings.
const SHARED: [StepId; 2] = [StepId::Read, StepId::Cleanup];

/// What the conversion thread hands back.
enum Message {
    Shared(Box<State>),
    Method(usize, Box<MethodResult>),
}

/// What the caller's thread received.
pub(super) struct Received {
    pub shared: Option<State>,
    pub results: Vec<Option<MethodResult>>,
    pub timed_out: bool,
    pub missing: String,
}

/// Runs the conversion thread and waits for it, within the time limit.
pub(super) fn run(request: &Request, caller: &Cancel, progress: Arc<dyn Progress>) -> Received {
    let start = Instant::now();
    let cancel = Cancel::default();
    let (tx, rx) = mpsc::channel::<Message>();
    let mut received = Received {
        shared: None,
        results: request.methods.iter().map(|_| None).collect(),
        timed_out: false,
        missing: "the conversion thread stopped without a result".into(),
    };
    let thread = {
        let (request, cancel) = (request.clone(), cancel.clone());
        // The caller's span (a batch's progress bar, a job) stays the parent of the steps'.
        let parent = tracing::Span::current();
        std::thread::Builder::new()
            .name(format!("convert {}", request.source.name()))
            .spawn(move || parent.in_scope(|| work(&request, &cancel, progress.as_ref(), &tx)))
    };
    let handle = match thread {
        Ok(handle) => handle,
        Err(e) => {
            received.missing = format!("cannot start a thread: {e}");
            return received;
        }
    };
    let deadline = request.timeout.map(|t| start + t);
    let mut pending = request.methods.len();
    while pending > 0 {
        if caller.is_cancelled() {
            cancel.cancel();
        }
        let wait = deadline.map_or(POLL, |d| d.saturating_duration_since(Instant::now()).min(POLL));
        match rx.recv_timeout(wait) {
            Ok(Message::Shared(state)) => received.shared = Some(*state),
            Ok(Message::Method(k, result)) => {
                received.results[k] = Some(*result);
                pending -= 1;
            }
            Err(RecvTimeoutError::Timeout) if deadline.is_some_and(|d| Instant::now() >= d) => {
                cancel.cancel();
                received.timed_out = true;
                drain_until(&rx, Instant::now() + CANCEL_GRACE);
                break;
            }
            Err(RecvTimeoutError::Timeout) => {}
            Err(RecvTimeoutError::Disconnected) => break,
        }
    }
    if !received.timed_out {
        let _ = handle.join();
    }
    received
}

/// Waits for the cancelled thread to stop, so it does not compete with the caller's next
/// work for the cores, but never past `until`: a step that checks rarely is left behind.
fn drain_until(rx: &mpsc::Receiver<Message>, until: Instant) {
    while let Ok(_) | Err(RecvTimeoutError::Timeout) = rx.recv_timeout(until.saturating_duration_since(Instant::now()))
    {
        if Instant::now() >= until {
            break;
        }
    }
}

/// Every method's result: those received, the rest timed out or lost.
pub(super) fn complete(
    request: &Request,
    results: Vec<Option<MethodResult>>,
    timed_out: bool,
    missing: &str,
) -> Vec<MethodResult> {
    let seconds = request.timeout.map_or(0.0, |t| t.as_secs_f64());
    request
        .methods
        .iter()
        .zip(results)
        .map(|(&method, result)| {
            result.unwrap_or_else(|| {
                let error = if timed_out {
                    Error::TimedOut { seconds }
                } else {
                    Error::Internal {
                        step: "convert",
                        problem: Internal::Thread {
                            message: missing.to_string(),
                        },
                    }
                };
                failed(method, error, None, 0.0)
            })
        })
        .collect()
}

fn failed(method: MethodKind, error: Error, state: Option<State>, seconds: f64) -> MethodResult {
    MethodResult {
        method,
        status: Status::of(&error),
        seconds,
        state,
        score: None,
        verification: None,
        error: Some(error),
    }
}

/// The conversion thread: shared steps, then every method in order.
fn work(request: &Request, cancel: &Cancel, progress: &dyn Progress, tx: &Sender<Message>) {
    let send = |k: usize, result: MethodResult| {
        progress.event(Event::Method(&result));
        tx.send(Message::Method(k, Box::new(result))).is_ok()
    };
    let shared = catch(|| shared_steps(request, cancel, progress));
    let base = match shared {
        Ok((state, Ok(()))) => state,
        Ok((state, Err(error))) => {
            for (k, &method) in request.methods.iter().enumerate() {
                send(k, failed(method, error.clone(), Some(state.clone()), 0.0));
            }
            return;
        }
        Err(panic) => {
            for (k, &method) in request.methods.iter().enumerate() {
                let error = Error::Internal {
                    step: "convert",
                    problem: panic.clone(),
                };
                send(k, failed(method, error, None, 0.0));
            }
            return;
        }
    };
    let _ = tx.send(Message::Shared(Box::new(base.clone())));
    let mut foundations: Vec<State> = Vec::new();
    for (k, &method) in request.methods.iter().enumerate() {
        let start = Instant::now();
        let span = tracing::info_span!("method", name = method.name());
        let _entered = span.enter();
        let outcome = catch(|| {
            let (state, ran) = run_method(method, &base, &mut foundations, request, cancel, progress);
            let judged = ran.is_ok().then(|| judge(&state)).flatten();
            (state, judged, ran)
        });
        let seconds = start.elapsed().as_secs_f64();
        let result = match outcome {
            Ok((state, judged, Ok(()))) => {
                let (score, verification) = judged.map_or((None, None), |(s, v)| (Some(s), Some(v)));
                MethodResult {
                    method,
                    status: Status::Converted,
                    seconds,
                    state: Some(state),
                    score,
                    verification,
                    error: None,
                }
            }
            Ok((state, _, Err(error))) => failed(method, error, Some(state), seconds),
            Err(panic) => failed(
                method,
                Error::Internal {
                    step: "convert",
                    problem: panic,
                },
                None,
                seconds,
            ),
        };
        if !send(k, result) {
            break;
        }
    }
}

/// The state a run reached, and whether it finished.
type Outcome = (State, Result<(), Error>);

/// The steps every method shares, run once.
fn shared_steps(request: &Request, cancel: &Cancel, progress: &dyn Progress) -> Outcome {
    let mut state = State::new(request.source.clone(), request.settings.clone());
    if let Err(e) = request.settings.validate() {
        return (state, Err(e));
    }
    let observe = |event: StepEvent<'_>| progress.event(Event::Step { method: None, event });
    let ran = pipeline::run_observed(&SHARED, &mut state, cancel, &observe);
    (state, ran)
}

/// One method from the shared state: the foundation (reused when an earlier method ran it with
/// the same settings), then its own steps and the cutting plan.
fn run_method(
    method: MethodKind,
    base: &State,
    foundations: &mut Vec<State>,
    request: &Request,
    cancel: &Cancel,
    progress: &dyn Progress,
) -> Outcome {
    let settings = method.adjust(request.settings.clone());
    let steps = StepId::of_method(method);
    // The foundation is the steps a method starts with that others share; another method's
    // foundation may have run further (the classifier makes its own planar groups).
    let shared: Vec<StepId> = steps.iter().copied().take_while(|s| FOUNDATION.contains(s)).collect();
    let mut state = match foundations.iter().find(|s| *s.settings == settings) {
        Some(done) => done.clone().keeping(&shared),
        None => State {
            settings: Arc::new(settings),
            ..base.clone()
        },
    };
    if let Err(e) = inject(method, &request.faults, cancel) {
        return (state, Err(e));
    }
    let observe = |event: StepEvent<'_>| {
        progress.event(Event::Step {
            method: Some(method),
            event,
        })
    };
    let todo: Vec<StepId> = steps
        .into_iter()
        .filter(|s| !state.records.iter().any(|r| r.name == s.name()))
        .collect();
    let (foundation, rest): (Vec<StepId>, Vec<StepId>) = todo.into_iter().partition(|s| shared.contains(s));
    let ran = pipeline::run_observed(&foundation, &mut state, cancel, &observe)
        .and_then(|()| {
            if !foundation.is_empty() {
                foundations.push(state.clone());
            }
            pipeline::run_observed(&rest, &mut state, cancel, &observe)
        })
        .and_then(|()| has_parts(method, &state));
    (state, ran)
}

/// An empty plan is nothing to cut: a failure, whose step warnings say why.
fn has_parts(method: MethodKind, state: &State) -> Result<(), Error> {
    match &state.export {
        Some(bundle) if bundle.plan.parts.is_empty() => Err(Error::model(
            state.model_name(),
            ModelProblem::NoParts { method: method.name() },
        )),
        _ => Ok(()),
    }
}

/// The score and `verify`'s verdict of a converted method's plan, both from one analysis of
/// its assembly against the method's mesh, so they cannot disagree.
fn judge(state: &State) -> Option<(Score, Verification)> {
    let (mesh, bundle) = (state.mesh.as_deref()?, state.export.as_deref()?);
    let analysis = analyse(&bundle.plan, Some(mesh));
    let score = score::score_analysed(mesh, bundle, state.plates.as_deref(), &analysis);
    let mut verification = verify::check(&bundle.plan, &analysis, verify::MIN_COVERAGE);
    // The tie-break between methods scored alike (`best_of`).
    verification.volume_inside = Some(verify::volume_inside(&bundle.plan, mesh, &analysis));
    Some((score, verification))
}

/// Fails, panics or hangs as a caller's test asked for `method`.
fn inject(method: MethodKind, faults: &[Fault], cancel: &Cancel) -> Result<(), Error> {
    if let Some(fault) = faults.iter().find(|f| f.method == method) {
        match fault.kind {
            FaultKind::Error => {
                return Err(Error::Internal {
                    step: "convert",
                    problem: Internal::Injected { method: method.name() },
                });
            }
            FaultKind::Panic => panic!("the {} method was asked to panic (fault injection)", method.name()),
            FaultKind::Hang => {
                while !cancel.is_cancelled() {
                    std::thread::sleep(Duration::from_millis(5));
                }
                return Err(Error::Cancelled { step: "convert" });
            }
        }
    }
    Ok(())
}
