//! The conversion's threads: the shared steps once, then every method on a thread of its own
//! with a time budget of its own, each caught, scored and handed back over a channel while
//! the caller's thread keeps every method's time (docs/decisions.md, "convert").

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError, Sender};
use std::sync::{Arc, Mutex, OnceLock};
use std::time::{Duration, Instant};

use super::panic::catch;
use super::{Event, Fault, FaultKind, MethodResult, Progress, Request, Status};
use crate::assembly::analyse;
use crate::context::Cancel;
use crate::error::{Error, Internal, ModelProblem};
use crate::method::MethodKind;
use crate::pipeline::{self, State, StepEvent, StepId};
use crate::score::{self, Score};
use crate::settings::Settings;
use crate::verify::{self, Verification};

/// How long cancelled threads are waited for before they are left behind.
const CANCEL_GRACE: Duration = Duration::from_secs(2);
/// How often the caller's cancel handle is looked at while waiting.
const POLL: Duration = Duration::from_millis(50);
/// The steps every method runs with the same settings.
const SHARED: [StepId; 2] = [StepId::Read, StepId::Cleanup];
/// The steps methods that weld alike share: run once per weld setting, by the first method
/// that needs them, while the others that need them wait.
const WELDED: [StepId; 2] = [StepId::Weld, StepId::Mesh];

/// What the conversion's threads hand back.
enum Message {
    Shared(Box<Result<Outcome, Internal>>),
    Method(usize, Box<MethodResult>),
}

/// The state a run reached, and whether it finished.
type Outcome = (State, Result<(), Error>);

/// What a method's thread caught: its state, its plan's judgement, whether it finished; or
/// its panic.
type Caught = Result<(State, Option<(Score, Verification)>, Result<(), Error>), Internal>;

/// One method of the request, as the caller's thread sees it.
struct Slot {
    method: MethodKind,
    /// Stops this method alone (its budget ran out, or the caller cancelled).
    cancel: Cancel,
    /// Whether the method's events still reach the observer; whoever turns it off first (the
    /// method, finished, or the caller, at its deadline) tells the observer how it ended.
    live: Arc<AtomicBool>,
    deadline: Option<Instant>,
    started: Option<Instant>,
    result: Option<MethodResult>,
    /// Its thread sent its result (it may stay running after a timeout until it does).
    returned: bool,
}

/// Runs the conversion: the shared steps, then the methods side by side, at most
/// `request.parallel` at once, each within `request.timeout` of its start.
pub(super) fn run(
    request: &Request,
    caller: &Cancel,
    progress: Arc<dyn Progress>,
) -> (Option<State>, Vec<MethodResult>) {
    let start = Instant::now();
    let request = Arc::new(request.clone());
    let all = Cancel::default();
    let live = Arc::new(AtomicBool::new(true));
    let (tx, rx) = mpsc::channel::<Message>();
    let shared = {
        let (request, all, tx) = (request.clone(), all.clone(), tx.clone());
        let gated: Arc<dyn Progress> = Arc::new(Gate {
            live: live.clone(),
            inner: progress.clone(),
        });
        spawn(format!("convert {}", request.source.name()), move || {
            let outcome = catch(|| shared_steps(&request, &all, gated.as_ref()));
            let _ = tx.send(Message::Shared(Box::new(outcome)));
        })
    };
    let base = match shared.and_then(|()| wait_shared(&rx, caller, &all, (start, request.timeout))) {
        Ok((state, Ok(()))) => state,
        Ok((state, Err(error))) => return (Some(state.clone()), every(&request, &error, Some(state))),
        Err(error) => return (None, every(&request, &error, None)),
    };
    let methods = Scheduler {
        request: request.clone(),
        slots: request.methods.iter().map(|&m| Slot::new(m)).collect(),
        base: Arc::new(base.clone()),
        foundations: Arc::new(Foundations::default()),
        budget: request.timeout.map(|t| t.saturating_sub(start.elapsed())),
        limit: request.timeout.map_or(0.0, |t| t.as_secs_f64()),
        all: all.clone(),
        cancelled: false,
        progress,
        tx,
    }
    .run(&rx, caller);
    live.store(false, Ordering::SeqCst);
    (Some(base), methods)
}

/// Starts a named thread; the caller's span (a batch's progress bar, a job) stays the parent
/// of the steps' spans.
fn spawn(name: String, f: impl FnOnce() + Send + 'static) -> Result<(), Error> {
    let parent = tracing::Span::current();
    std::thread::Builder::new()
        .name(name)
        .spawn(move || parent.in_scope(f))
        .map(drop)
        .map_err(|e| Error::Internal {
            step: "convert",
            problem: Internal::Thread {
                message: format!("cannot start a thread: {e}"),
            },
        })
}

/// Waits for the shared steps, begun at `start`, within the `timeout` (they count against
/// every method's limit).
fn wait_shared(
    rx: &Receiver<Message>,
    caller: &Cancel,
    all: &Cancel,
    (start, timeout): (Instant, Option<Duration>),
) -> Result<Outcome, Error> {
    let deadline = timeout.map(|t| start + t);
    loop {
        if caller.is_cancelled() {
            all.cancel();
        }
        let wait = deadline.map_or(POLL, |d| d.saturating_duration_since(Instant::now()).min(POLL));
        match rx.recv_timeout(wait) {
            Ok(Message::Shared(caught)) => {
                return (*caught).map_err(|panic| Error::Internal {
                    step: "convert",
                    problem: panic,
                });
            }
            Ok(Message::Method(..)) => {}
            Err(RecvTimeoutError::Timeout) if deadline.is_some_and(|d| Instant::now() >= d) => {
                all.cancel();
                let seconds = timeout.map_or(0.0, |t| t.as_secs_f64());
                return Err(Error::TimedOut { seconds });
            }
            Err(RecvTimeoutError::Timeout) => {}
            Err(RecvTimeoutError::Disconnected) => {
                return Err(Error::Internal {
                    step: "convert",
                    problem: Internal::Thread {
                        message: "the conversion thread stopped without a result".into(),
                    },
                });
            }
        }
    }
}

/// The same failure for every method (the shared steps failed).
fn every(request: &Request, error: &Error, state: Option<State>) -> Vec<MethodResult> {
    request
        .methods
        .iter()
        .map(|&m| failed(m, error.clone(), state.clone(), 0.0))
        .collect()
}

impl Slot {
    fn new(method: MethodKind) -> Self {
        Self {
            method,
            cancel: Cancel::default(),
            live: Arc::new(AtomicBool::new(true)),
            deadline: None,
            started: None,
            result: None,
            returned: false,
        }
    }

    fn running(&self) -> bool {
        self.started.is_some() && self.result.is_none()
    }

    fn seconds(&self) -> f64 {
        self.started.map_or(0.0, |s| s.elapsed().as_secs_f64())
    }
}

/// Starts the methods, keeps their deadlines and collects their results.
struct Scheduler {
    request: Arc<Request>,
    slots: Vec<Slot>,
    base: Arc<State>,
    foundations: Arc<Foundations>,
    /// Each method's time from its start (the model's limit less the shared steps' time).
    budget: Option<Duration>,
    /// The limit as asked for, seconds, for messages.
    limit: f64,
    /// Stops the welded foundations once no method needs them.
    all: Cancel,
    /// The caller cancelled: methods still running after the grace period are reported
    /// cancelled.
    cancelled: bool,
    progress: Arc<dyn Progress>,
    tx: Sender<Message>,
}

impl Scheduler {
    fn run(mut self, rx: &Receiver<Message>, caller: &Cancel) -> Vec<MethodResult> {
        let parallel = match self.request.parallel {
            0 => self.slots.len(),
            p => p,
        };
        while self.slots.iter().any(|s| s.result.is_none()) {
            if caller.is_cancelled() && !self.cancelled {
                self.cancel_all();
            }
            while self.slots.iter().filter(|s| s.running()).count() < parallel
                && let Some(k) = self.slots.iter().position(|s| s.started.is_none())
            {
                self.start(k);
            }
            let now = Instant::now();
            let next = self
                .slots
                .iter()
                .filter(|s| s.running())
                .filter_map(|s| s.deadline)
                .min();
            let wait = next.map_or(POLL, |d| d.saturating_duration_since(now).min(POLL));
            match rx.recv_timeout(wait) {
                Ok(message) => self.receive(message),
                Err(RecvTimeoutError::Timeout) => self.expire(),
                Err(RecvTimeoutError::Disconnected) => break,
            }
        }
        self.all.cancel();
        self.drain(rx);
        let seconds = self.limit;
        self.slots
            .into_iter()
            .map(|s| {
                s.live.store(false, Ordering::SeqCst);
                let lost = Error::TimedOut { seconds };
                s.result.unwrap_or_else(|| failed(s.method, lost, None, 0.0))
            })
            .collect()
    }

    /// Starts method `k` on a thread of its own.
    fn start(&mut self, k: usize) {
        let now = Instant::now();
        let slot = &mut self.slots[k];
        slot.started = Some(now);
        slot.deadline = self.budget.map(|b| now + b);
        let job = MethodJob {
            k,
            method: slot.method,
            request: self.request.clone(),
            base: self.base.clone(),
            foundations: self.foundations.clone(),
            cancel: slot.cancel.clone(),
            all: self.all.clone(),
            live: slot.live.clone(),
            progress: self.progress.clone(),
        };
        let tx = self.tx.clone();
        let name = format!("{} {}", slot.method.name(), self.request.source.name());
        if let Err(error) = spawn(name, move || job.run(&tx)) {
            slot.live.store(false, Ordering::SeqCst);
            slot.returned = true;
            slot.result = Some(failed(slot.method, error, None, 0.0));
        }
    }

    fn receive(&mut self, message: Message) {
        if let Message::Method(k, result) = message {
            let slot = &mut self.slots[k];
            slot.returned = true;
            if slot.result.is_none() {
                slot.result = Some(*result);
            }
        }
    }

    /// Cancels every running method past its deadline and reports it timed out (or, after
    /// the caller cancelled, cancelled), alone.
    fn expire(&mut self) {
        let now = Instant::now();
        let seconds = self.limit;
        for slot in self.slots.iter_mut().filter(|s| s.running()) {
            if slot.deadline.is_some_and(|d| now >= d) && slot.live.swap(false, Ordering::SeqCst) {
                slot.cancel.cancel();
                let error = if self.cancelled {
                    Error::Cancelled { step: "convert" }
                } else {
                    Error::TimedOut { seconds }
                };
                let mut result = failed(slot.method, error, None, 0.0);
                result.seconds = slot.seconds();
                self.progress.event(Event::Method(&result));
                slot.result = Some(result);
            }
        }
    }

    /// The caller cancelled: running methods stop at their next check and say so; those not
    /// started never start.
    fn cancel_all(&mut self) {
        self.cancelled = true;
        self.all.cancel();
        let grace = Instant::now() + CANCEL_GRACE;
        for slot in &mut self.slots {
            slot.cancel.cancel();
            slot.deadline = Some(slot.deadline.map_or(grace, |d| d.min(grace)));
            if slot.started.is_none() && slot.live.swap(false, Ordering::SeqCst) {
                slot.started = Some(Instant::now());
                slot.returned = true;
                let result = failed(slot.method, Error::Cancelled { step: "convert" }, None, 0.0);
                self.progress.event(Event::Method(&result));
                slot.result = Some(result);
            }
        }
    }

    /// Waits for cancelled threads to stop, so they do not compete with the caller's next
    /// work for the cores, but never past the grace period: a step that checks rarely is left
    /// behind (its events no longer reach anyone).
    fn drain(&mut self, rx: &Receiver<Message>) {
        let until = Instant::now() + CANCEL_GRACE;
        while self.slots.iter().any(|s| s.started.is_some() && !s.returned) {
            match rx.recv_timeout(until.saturating_duration_since(Instant::now())) {
                Ok(message) => self.receive(message),
                Err(_) => break,
            }
        }
    }
}

/// Everything a method's thread needs.
struct MethodJob {
    k: usize,
    method: MethodKind,
    request: Arc<Request>,
    base: Arc<State>,
    foundations: Arc<Foundations>,
    cancel: Cancel,
    all: Cancel,
    live: Arc<AtomicBool>,
    progress: Arc<dyn Progress>,
}

impl MethodJob {
    /// Runs, judges and hands back the method; its events reach the observer while it is live.
    fn run(self, tx: &Sender<Message>) {
        let span = tracing::info_span!("method", name = self.method.name());
        let _entered = span.enter();
        let start = Instant::now();
        let gated = Gate {
            live: self.live.clone(),
            inner: self.progress.clone(),
        };
        let outcome = catch(|| {
            let (state, ran) = self.steps(&gated);
            let judged = ran.is_ok().then(|| judge(&state)).flatten();
            (state, judged, ran)
        });
        let result = result_of(self.method, outcome, start.elapsed().as_secs_f64());
        if self.live.swap(false, Ordering::SeqCst) {
            self.progress.event(Event::Method(&result));
        }
        let _ = tx.send(Message::Method(self.k, Box::new(result)));
    }

    /// The method's steps from the shared state: the welded foundation (shared with the
    /// methods that weld alike), then its own steps and the cutting plan.
    fn steps(&self, progress: &dyn Progress) -> Outcome {
        let (method, request) = (self.method, &self.request);
        let settings = method.adjust(request.settings.clone());
        let observe = |event: StepEvent<'_>| {
            progress.event(Event::Step {
                method: Some(method),
                event,
            })
        };
        if let Err(e) = inject(method, &request.faults, &self.cancel) {
            let state = State {
                settings: Arc::new(settings),
                ..(*self.base).clone()
            };
            return (state, Err(e));
        }
        let steps = StepId::of_method(method);
        let welded: Vec<StepId> = steps.iter().copied().filter(|s| WELDED.contains(s)).collect();
        let (mut state, ran) = self
            .foundations
            .cell(&settings)
            .get_or_init(|| {
                let mut state = State {
                    settings: Arc::new(settings.clone()),
                    ..(*self.base).clone()
                };
                // Stopped only when no method needs it any more: another may be waiting.
                let ran = pipeline::run_observed(&welded, &mut state, &self.all, &observe);
                (state, ran)
            })
            .clone();
        if ran.is_err() {
            return (state, ran);
        }
        // The classifier skips exact faces only beside the plate method, whose plan it would
        // repeat; asked for alone, it runs.
        if method == MethodKind::Classifier && !request.methods.contains(&MethodKind::Plate) {
            let mut own = (*state.settings).clone();
            own.classify_exact_faces = true;
            state.settings = Arc::new(own);
        }
        let todo: Vec<StepId> = steps
            .into_iter()
            .filter(|s| !state.records.iter().any(|r| r.name == s.name()))
            .collect();
        let ran =
            pipeline::run_observed(&todo, &mut state, &self.cancel, &observe).and_then(|()| has_parts(method, &state));
        (state, ran)
    }
}

/// The welded foundations, one per distinct settings, each made once by the first method that
/// needs it.
#[derive(Default)]
struct Foundations(Mutex<Vec<(Settings, Arc<OnceLock<Outcome>>)>>);

impl Foundations {
    fn cell(&self, settings: &Settings) -> Arc<OnceLock<Outcome>> {
        let mut cells = self.0.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        if let Some((_, cell)) = cells.iter().find(|(s, _)| s == settings) {
            return cell.clone();
        }
        let cell = Arc::new(OnceLock::new());
        cells.push((settings.clone(), cell.clone()));
        cell
    }
}

/// A method's result from what its thread caught.
fn result_of(method: MethodKind, outcome: Caught, seconds: f64) -> MethodResult {
    match outcome {
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
    }
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

/// The steps every method shares, run once.
fn shared_steps(request: &Request, cancel: &Cancel, progress: &dyn Progress) -> Outcome {
    let mut state = State::new(request.source.clone(), request.settings.clone());
    if let Err(e) = request.settings.validate() {
        return (state, Err(e));
    }
    let observe = |event: StepEvent<'_>| progress.event(Event::Step { method: None, event });
    let ran = pipeline::run_observed(&SHARED, &mut state, cancel, &observe);
    progress.event(Event::Shared(&state));
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
    // The verdict carries the tie-break between methods scored alike (`best_of`): the share
    // of volume inside, from the same analysis.
    let verification = verify::check(&bundle.plan, &analysis, verify::MIN_COVERAGE);
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

/// Forwards events while `live`; a thread left behind after its time limit reports nothing
/// more.
struct Gate {
    live: Arc<AtomicBool>,
    inner: Arc<dyn Progress>,
}

impl Progress for Gate {
    fn event(&self, event: Event<'_>) {
        if self.live.load(Ordering::SeqCst) {
            self.inner.event(event);
        }
    }
}
