-- Jobs, their progress events and their results (issue 17). Times are milliseconds since
-- 1970 written by the program, so both databases store the same numbers.
CREATE TABLE jobs (
    id TEXT PRIMARY KEY,
    status TEXT NOT NULL,
    name TEXT NOT NULL,
    model BLOB NOT NULL,
    model_bytes BIGINT NOT NULL,
    triangles BIGINT,
    settings TEXT NOT NULL,
    created BIGINT NOT NULL,
    started BIGINT,
    finished BIGINT,
    attempts BIGINT NOT NULL DEFAULT 0,
    lease_until BIGINT,
    worker TEXT,
    error TEXT,
    summary TEXT,
    delete_token TEXT NOT NULL,
    published BIGINT,
    parent TEXT
);
CREATE INDEX jobs_queue ON jobs (status, created);
CREATE INDEX jobs_published ON jobs (published);

CREATE TABLE events (
    job_id TEXT NOT NULL,
    seq BIGINT NOT NULL,
    kind TEXT NOT NULL,
    data TEXT NOT NULL,
    PRIMARY KEY (job_id, seq)
);

CREATE TABLE results (
    job_id TEXT NOT NULL,
    method TEXT NOT NULL,
    file TEXT NOT NULL,
    content_type TEXT NOT NULL,
    data BLOB NOT NULL,
    PRIMARY KEY (job_id, method, file)
);

CREATE TABLE meta (
    key TEXT PRIMARY KEY,
    value TEXT NOT NULL
);
