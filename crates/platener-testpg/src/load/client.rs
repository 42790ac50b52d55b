//! One simulated user: upload the model, follow its events while reading its status now and
//! then, confirm the status, download the plan.

use std::sync::Arc;
use std::time::Instant;

use futures_util::StreamExt;
use reqwest::{Client, RequestBuilder, Response, StatusCode};

use super::Config;
use super::sse::Parser;
use super::stats::Recorder;

/// How one conversion ended for the client.
enum Outcome {
    /// The upload was not accepted (already counted as a failed request).
    NotSubmitted,
    /// `done`, and the plan was downloaded.
    Done,
    /// `failed`, or broken off by a failed request.
    Failed,
}

/// Runs one client's conversions one after the other.
pub(crate) async fn run_client(http: Client, config: Arc<Config>) -> Recorder {
    let mut rec = Recorder::default();
    for _ in 0..config.conversions_per_client {
        let started = Instant::now();
        let submitted_before = rec.submitted;
        match tokio::time::timeout(config.timeout, conversion(&http, &config, &mut rec)).await {
            Ok(Outcome::NotSubmitted) => {}
            Ok(Outcome::Done) => {
                rec.done += 1;
                rec.conversion_ms.push(ms_since(started));
            }
            Ok(Outcome::Failed) => rec.failed += 1,
            Err(_) => {
                rec.error(format!(
                    "conversion: not finished within {} s",
                    config.timeout.as_secs()
                ));
                if rec.submitted > submitted_before {
                    rec.failed += 1;
                }
            }
        }
    }
    rec
}

/// One conversion from upload to plan.
async fn conversion(http: &Client, config: &Config, rec: &mut Recorder) -> Outcome {
    let Some(id) = upload(http, config, rec).await else {
        return Outcome::NotSubmitted;
    };
    rec.submitted += 1;
    let url = format!("{}/api/conversions/{id}", config.base_url);
    read_status(http, &url, rec).await;
    let Some(ended) = follow_events(http, config, &url, rec).await else {
        return Outcome::Failed;
    };
    // The API promises the conversion's status agrees with its last event.
    if let Some(status) = read_status(http, &url, rec).await
        && status != ended
    {
        rec.error(format!("status: {status} after the {ended} event"));
    }
    if ended == "done" && download_plan(http, &url, rec).await {
        Outcome::Done
    } else {
        Outcome::Failed
    }
}

/// `POST /api/conversions` with the model; the new conversion's id.
async fn upload(http: &Client, config: &Config, rec: &mut Recorder) -> Option<String> {
    let part = reqwest::multipart::Part::bytes(config.model.clone())
        .file_name(config.model_name.clone())
        .mime_str("application/octet-stream")
        .ok()?;
    let form = reqwest::multipart::Form::new().part("model", part);
    let request = http
        .post(format!("{}/api/conversions", config.base_url))
        .multipart(form);
    let started = Instant::now();
    let response = send(rec, "upload", request, StatusCode::ACCEPTED).await?;
    let body: serde_json::Value = json(rec, "upload", response).await?;
    rec.upload_ms.push(ms_since(started));
    let id = body.get("id").and_then(|v| v.as_str()).map(str::to_string);
    if id.is_none() {
        rec.error("upload: no id in the answer".into());
    }
    id
}

/// `GET /api/conversions/{id}`, timed; the conversion's status.
async fn read_status(http: &Client, url: &str, rec: &mut Recorder) -> Option<String> {
    let started = Instant::now();
    let response = send(rec, "status", http.get(url), StatusCode::OK).await?;
    let body: serde_json::Value = json(rec, "status", response).await?;
    rec.status_ms.push(ms_since(started));
    let status = body.get("status").and_then(|v| v.as_str()).map(str::to_string);
    if status.is_none() {
        rec.error("status: no status in the answer".into());
    }
    status
}

/// Streams `GET …/events` until `done` or `failed` (returned), reading the status every
/// `status_interval` meanwhile (at most `status_reads_while_streaming` times), as a page
/// showing progress would.
async fn follow_events(http: &Client, config: &Config, url: &str, rec: &mut Recorder) -> Option<String> {
    let request = http.get(format!("{url}/events")).header("Accept", "text/event-stream");
    let mut stream = send(rec, "events", request, StatusCode::OK).await?.bytes_stream();
    let mut parser = Parser::default();
    let mut tick = tokio::time::interval(config.status_interval);
    tick.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Delay);
    tick.tick().await;
    let mut reads = 0;
    let limit = config.status_reads_while_streaming;
    loop {
        tokio::select! {
            chunk = stream.next() => match chunk {
                Some(Ok(bytes)) => {
                    let events = parser.push(&bytes);
                    if let Some(event) = events.into_iter().find(|e| e.name == "done" || e.name == "failed") {
                        return Some(event.name);
                    }
                }
                Some(Err(e)) => {
                    rec.error(format!("events: {}", e.without_url()));
                    return None;
                }
                None => {
                    rec.error("events: the stream ended before done or failed".into());
                    return None;
                }
            },
            _ = tick.tick(), if limit == 0 || reads < limit => {
                reads += 1;
                read_status(http, url, rec).await;
            }
        }
    }
}

/// `GET …/plan.zip`; whether a whole ZIP holding `plan.json` came back.
async fn download_plan(http: &Client, url: &str, rec: &mut Recorder) -> bool {
    let started = Instant::now();
    let Some(response) = send(rec, "plan", http.get(format!("{url}/plan.zip")), StatusCode::OK).await else {
        return false;
    };
    match response.bytes().await {
        Ok(bytes) if super::zipdir::names(&bytes).is_some_and(|n| n.iter().any(|n| n == "plan.json")) => {
            rec.plan_ms.push(ms_since(started));
            rec.plan_bytes += bytes.len() as u64;
            true
        }
        Ok(_) => {
            rec.error("plan: not a ZIP holding plan.json".into());
            false
        }
        Err(e) => {
            rec.error(format!("plan: {}", e.without_url()));
            false
        }
    }
}

/// Sends a request, counting it, and keeps the response only when its status is `expect`.
async fn send(rec: &mut Recorder, what: &str, request: RequestBuilder, expect: StatusCode) -> Option<Response> {
    rec.requests += 1;
    match request.send().await {
        Ok(response) if response.status() == expect => Some(response),
        Ok(response) => {
            rec.error(format!("{what}: HTTP {}", response.status().as_u16()));
            None
        }
        Err(e) => {
            rec.error(format!("{what}: {}", e.without_url()));
            None
        }
    }
}

/// A response's JSON body, a failed request when it is not JSON.
async fn json(rec: &mut Recorder, what: &str, response: Response) -> Option<serde_json::Value> {
    match response.json().await {
        Ok(value) => Some(value),
        Err(e) => {
            rec.error(format!("{what}: {}", e.without_url()));
            None
        }
    }
}

fn ms_since(start: Instant) -> f64 {
    start.elapsed().as_secs_f64() * 1000.0
}
