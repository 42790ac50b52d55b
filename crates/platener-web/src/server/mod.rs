//! `platener serve`: the HTTP API of ../shared/spec/api.md over the job database, with the
//! worker processes it starts and restarts.
//!
//! The server never converts: it reads each upload's model ([`inspect`]: the library's `read`
//! step, so an unreadable one is a `422`), stores it as a queued job (before answering `202`), reads
//! jobs, events and result files back, and supervises `platener worker` processes
//! ([`workers`]). Several servers may share one PostgreSQL database.

mod api;
mod assets;
mod cancel;
mod debug;
mod error;
mod events;
mod examples;
mod files;
mod gallery;
mod health;
mod inspect;
mod limits;
mod metrics;
mod page;
mod publish;
mod settings;
mod strip;
mod view;
mod workers;

use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;
use std::time::Duration;

use axum::Router;
use axum::extract::DefaultBodyLimit;
use axum::http::{HeaderName, HeaderValue};
use axum::routing::get;
use tokio::sync::watch;
use tower_http::set_header::SetResponseHeaderLayer;
use tower_http::timeout::TimeoutLayer;

use crate::db::{Db, DbError};

pub use error::{ApiError, ApiResult};

/// How the server runs (`platener serve`'s flags).
#[derive(Debug, Clone)]
pub struct ServeConfig {
    /// Where to listen (port 0: any free port; the callback gets the real one).
    pub addr: SocketAddr,
    /// The folder of the SQLite database (created if missing).
    pub data: PathBuf,
    /// The database URL; `None`: SQLite at `data/platener.sqlite`.
    pub database: Option<String>,
    /// Worker processes to start (0: none, for a server whose workers run elsewhere).
    pub workers: usize,
    /// Largest upload, MB (10^6 bytes).
    pub max_upload_mb: u64,
    /// Largest model in triangles (a binary STL from its header, other formats once read at
    /// upload).
    pub max_triangles: u64,
    /// Time limit per model, seconds (0: none).
    pub timeout: f64,
    /// Queued jobs beyond which uploads get `503 busy`.
    pub max_queue: i64,
    /// Uploads per minute from one address before `429`.
    pub rate_limit: u32,
    /// How long a SIGTERM waits for running jobs before re-queuing them.
    pub grace: Duration,
    /// Queue and publish the shipped examples on the first start.
    pub examples: bool,
    /// The program started as `worker` (the `platener` binary itself).
    pub worker_exe: PathBuf,
    /// Memory limit per worker, MB (0: none).
    pub worker_memory_mb: u64,
    /// Let workers honour the test-only model names (`PLATENER_TEST_HOOKS=1`).
    pub test_hooks: bool,
    /// How long a worker's claim lasts without a heartbeat; a worker silent for half of it
    /// while it holds a job is killed and replaced.
    pub worker_lease: Duration,
}

impl ServeConfig {
    /// The defaults of `platener serve` with `worker_exe` as the worker program.
    pub fn new(worker_exe: PathBuf) -> Self {
        Self {
            addr: SocketAddr::from(([127, 0, 0, 1], 3000)),
            data: PathBuf::from("platener-data"),
            database: None,
            workers: std::thread::available_parallelism().map_or(1, |n| n.get()),
            max_upload_mb: 50,
            max_triangles: 5_000_000,
            timeout: 60.0,
            max_queue: 100,
            rate_limit: 30,
            grace: Duration::from_secs(20),
            examples: true,
            worker_exe,
            worker_memory_mb: 2048,
            test_hooks: false,
            worker_lease: Duration::from_millis(crate::worker::DEFAULT_LEASE_MS.unsigned_abs()),
        }
    }

    /// The database URL: the one given, or the SQLite file in the data folder.
    pub fn database_url(&self) -> String {
        self.database
            .clone()
            .unwrap_or_else(|| format!("sqlite://{}?mode=rwc", self.data.join("platener.sqlite").display()))
    }

    fn max_upload_bytes(&self) -> usize {
        usize::try_from(self.max_upload_mb.saturating_mul(1_000_000)).unwrap_or(usize::MAX)
    }
}

/// Why the server could not start or stopped.
#[derive(Debug, thiserror::Error)]
pub enum ServeError {
    /// The database failed.
    #[error(transparent)]
    Db(#[from] DbError),
    /// Listening, the data folder or the runtime failed.
    #[error("{0}")]
    Io(#[from] std::io::Error),
}

/// What every handler shares.
#[derive(Debug)]
pub(crate) struct App {
    pub db: Db,
    pub config: ServeConfig,
    /// Set by SIGTERM: uploads are refused while running jobs finish.
    pub draining: AtomicBool,
    /// What each of this server's workers is doing.
    pub roster: workers::Roster,
    pub limiter: limits::RateLimiter,
    pub metrics: metrics::Metrics,
    /// Becomes true when the server stops: event streams end.
    pub stopping: watch::Receiver<bool>,
    /// The one reader of new events, feeding every event stream of this process.
    pub events: Arc<events::Hub>,
}

/// Runs the server until SIGTERM or Ctrl-C; `on_listening` gets the bound address (to print).
pub fn serve(config: ServeConfig, on_listening: impl FnOnce(SocketAddr) + Send + 'static) -> Result<(), ServeError> {
    let runtime = tokio::runtime::Builder::new_multi_thread().enable_all().build()?;
    runtime.block_on(run(config, on_listening))
}

async fn run(config: ServeConfig, on_listening: impl FnOnce(SocketAddr) + Send + 'static) -> Result<(), ServeError> {
    if config.database.is_none() {
        std::fs::create_dir_all(&config.data)?;
    }
    let db = Db::connect(&config.database_url(), 8).await?;
    if config.examples {
        examples::seed(&db).await?;
    }
    let listener = tokio::net::TcpListener::bind(config.addr).await?;
    let (stop_tx, stop_rx) = watch::channel(false);
    let hub = events::Hub::new(db.clone(), events::EVENT_POLL);
    let listen_url = (db.dialect() == crate::db::Dialect::Postgres).then(|| config.database_url());
    hub.start(listen_url, stop_rx.clone());
    let app = Arc::new(App {
        db,
        events: hub,
        draining: AtomicBool::new(false),
        roster: workers::Roster::default(),
        limiter: limits::RateLimiter::new(config.rate_limit),
        metrics: metrics::Metrics::default(),
        stopping: stop_rx.clone(),
        config,
    });
    let pool = workers::start(app.clone(), stop_rx);
    on_listening(listener.local_addr()?);
    let shutdown = {
        let app = app.clone();
        async move {
            wait_for_signal().await;
            tracing::info!("stopping: no new uploads; waiting for running jobs");
            app.draining.store(true, std::sync::atomic::Ordering::SeqCst);
            pool.drain(app.config.grace).await;
            let _ = stop_tx.send(true);
        }
    };
    axum::serve(
        listener,
        router(app.clone()).into_make_service_with_connect_info::<SocketAddr>(),
    )
    .with_graceful_shutdown(shutdown)
    .await?;
    app.db.close().await;
    Ok(())
}

async fn wait_for_signal() {
    let ctrl_c = tokio::signal::ctrl_c();
    match tokio::signal::unix::signal(tokio::signal::unix::SignalKind::terminate()) {
        Ok(mut term) => {
            tokio::select! {
                _ = ctrl_c => {}
                _ = term.recv() => {}
            }
        }
        Err(_) => {
            let _ = ctrl_c.await;
        }
    }
}

/// Every route. Event streams are left out of the request timeout; everything gets
/// `nosniff` and no referrer.
fn router(app: Arc<App>) -> Router {
    let body_limit = app.config.max_upload_bytes() + api::FORM_SLACK;
    // A router per resource; every one but the event streams under the request timeout.
    let timed = Router::new()
        .merge(page::routes())
        .merge(api::routes())
        .merge(files::routes())
        .merge(debug::routes())
        .merge(gallery::routes())
        .merge(strip::routes())
        .merge(health::routes())
        .merge(metrics::routes())
        .layer(TimeoutLayer::with_status_code(
            axum::http::StatusCode::REQUEST_TIMEOUT,
            Duration::from_secs(60),
        ));
    Router::new()
        .route("/api/conversions/{id}/events", get(events::events))
        .merge(timed)
        .fallback(error::not_found)
        .layer(DefaultBodyLimit::max(body_limit))
        .layer(axum::middleware::from_fn_with_state(
            app.clone(),
            metrics::count_requests,
        ))
        .layer(SetResponseHeaderLayer::overriding(
            HeaderName::from_static("x-content-type-options"),
            HeaderValue::from_static("nosniff"),
        ))
        .layer(SetResponseHeaderLayer::overriding(
            HeaderName::from_static("referrer-policy"),
            HeaderValue::from_static("no-referrer"),
        ))
        .with_state(app)
}
