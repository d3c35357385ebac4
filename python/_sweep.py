"""mote.sweep: many mote.replay runs (logs x configs x seeds) fanned out through dask.distributed,
gathered into one table. Dask is the scheduler; this module only builds the tasks and the rows.

dask is imported only when sweep() runs, so `import mote` works without it.
"""

import numbers
import os
from collections.abc import Mapping
from typing import NamedTuple, Optional

# The mote.replay keywords a log entry may carry; the sweep itself sets config, particles, seed
# and threads, and `out` would have every task write into the same folder.
LOG_KEYS = ("map", "log", "reference", "lenient", "laser_max_range", "init_pose")


class SweepRow(NamedTuple):
    """One task of a sweep: a log replayed under a config with a seed. A NamedTuple so that the
    table is a plain list: rows index like tuples, read like records (row.ate_rmse_m), write
    with csv.writer under SweepRow._fields, and pandas.DataFrame(rows) takes them as they are."""

    log: str  #: the log's name (its "name" key, its key in a mapping, else the log path)
    config: str  #: the config's name (its key in a mapping, its path, or the fields it changes)
    seed: int
    ate_rmse_m: Optional[float]  #: None without a reference (or when the task failed)
    heading_rmse_deg: Optional[float]
    update_ms: Optional[float]  #: median time per filter update (report update_ms.p50)
    particles: Optional[float]  #: mean particle count over the updates (KLD adapts it)
    updates: int
    error: Optional[str] = None  #: with errors="keep": the failed task's one-line message


class _Task(NamedTuple):
    """What one worker needs, in picklable values: LocalizerConfig is a C++ object without
    pickle support, so it travels as its fields and is rebuilt on the worker."""

    log: str
    config: str
    seed: int
    replay_kwargs: dict
    config_fields: dict
    particles: Optional[int]
    threads: int


def sweep(logs, configs, client=None, *, seed=42, particles=None, threads=1, n_workers=None,
          errors="raise"):
    """Replays every log under every config (and every seed) through dask.distributed and returns
    one SweepRow per run, in the order log, config, seed.

    logs: dicts of mote.replay keywords (map and log required; reference, init_pose, lenient,
      laser_max_range optional) with an optional "name", or a mapping {name: such dict}.
    configs: YAML paths, dicts of LocalizerConfig fields, LocalizerConfig objects or None (the
      defaults), or a mapping {name: one of those}. Paths are read here, on the client, so only
      the maps and logs have to be reachable from the workers.
    client: None starts a LocalCluster of n_workers single-threaded worker processes (default:
      usable cores // threads) and closes it afterwards; a scheduler address ("tcp://host:8786")
      connects to a running cluster; a distributed.Client is used as it is.
    seed: one seed or a sequence of them; replaces each config's seed, as mote.replay does.
    particles: fixes min = max particles for every run (None keeps each config's own).
    threads: mote's own threads per run. Start remote workers with `--nthreads 1` so that dask
      runs one replay per worker process and mote's threads are the only parallelism inside it.
    errors: "raise" cancels the remaining runs at the first mote.Error and raises it again, of
      the same class, its message prefixed by the log and config names; "keep" returns a row
      whose error holds that message instead.

    Every worker process must be able to `import mote`: local workers inherit this interpreter's
    environment (PYTHONPATH); remote ones need mote installed or on their own PYTHONPATH.
    """
    if errors not in ("raise", "keep"):
        raise ValueError(f"sweep: errors must be 'raise' or 'keep', not {errors!r}")
    seeds = [int(seed)] if isinstance(seed, numbers.Integral) else [int(s) for s in seed]
    named_logs, named_configs = _named_logs(logs), _named_configs(configs)
    tasks = [_Task(log_name, config_name, s, log_kwargs, fields, particles, threads)
             for log_name, log_kwargs in named_logs
             for config_name, fields in named_configs
             for s in seeds]
    if not tasks:
        return []
    results = _run(tasks, client, n_workers or _default_workers(len(tasks), threads),
                   stop_at_failure=errors == "raise")
    failed = [(t, r) for t, r in zip(tasks, results) if isinstance(r, _Failure)]
    if failed and errors == "raise":
        raise failed[0][1].exception(failed[0][0])
    return [_row(task, result) for task, result in zip(tasks, results)]


class _Failure(NamedTuple):
    """A mote.Error in a task, returned rather than raised so that it reaches the client as a
    plain value whatever the worker's pickling of C++-registered exception classes."""

    kind: str  # "InputError", "ConfigError" or "Error"
    message: str

    def text(self, task):
        return f"sweep: log {task.log!r}, config {task.config!r}, seed {task.seed}: {self.message}"

    def exception(self, task):
        import mote

        return getattr(mote, self.kind, mote.Error)(self.text(task))


def _replay_task(task):
    """Runs on a worker: one mote.replay, reduced to the table's figures (the trajectory and the
    rest of the report stay on the worker)."""
    import mote

    try:
        config = mote.LocalizerConfig(**task.config_fields)
        report = mote.replay(config=config, particles=task.particles, seed=task.seed,
                             threads=task.threads, **task.replay_kwargs)
    except mote.Error as e:
        kinds = [k for k in ("InputError", "ConfigError") if isinstance(e, getattr(mote, k))]
        return _Failure(kinds[0] if kinds else "Error", str(e))
    return {"ate_rmse_m": report.get("ate_rmse_m"),
            "heading_rmse_deg": report.get("heading_rmse_deg"),
            "update_ms": report["update_ms"]["p50"] if report["updates"] else None,
            "particles": report["particles_mean"] if report["updates"] else None,
            "updates": report["updates"]}


def _row(task, result):
    if isinstance(result, _Failure):
        return SweepRow(task.log, task.config, task.seed, None, None, None, None, 0,
                        result.text(task))
    return SweepRow(task.log, task.config, task.seed, **result)


def _run(tasks, client, n_workers, stop_at_failure):
    """The tasks' results in task order. With stop_at_failure, the first _Failure cancels the
    tasks still running or queued, and their results stay None."""
    try:
        import distributed
    except ImportError as e:
        raise ImportError("mote.sweep needs dask.distributed (Debian: python3-distributed)") from e
    client, close = _connect(distributed, client, n_workers)
    futures = []
    try:
        futures = [client.submit(_replay_task, t, pure=False) for t in tasks]
        index = {f.key: k for k, f in enumerate(futures)}
        results = [None] * len(tasks)
        for future, result in distributed.as_completed(futures, with_results=True):
            results[index[future.key]] = result
            if stop_at_failure and isinstance(result, _Failure):
                break
        return results
    except ModuleNotFoundError as e:  # raised by a worker unpickling _replay_task
        if e.name != "mote":
            raise
        raise ModuleNotFoundError("sweep: a dask worker cannot import mote: install mote where the "
                                  "workers run, or start them with PYTHONPATH=BUILD/python",
                                  name="mote") from e
    finally:
        client.cancel(futures)  # nothing left behind on a shared cluster, even on Ctrl-C
        close()


def _connect(distributed, client, n_workers):
    """(a Client, what closes what this call opened)."""
    if client is None:
        # Processes, one thread each: a replay releases the GIL, but one task per process keeps
        # mote's own thread pool (threads) the only parallelism inside a worker.
        cluster = distributed.LocalCluster(n_workers=n_workers, threads_per_worker=1,
                                           processes=True, dashboard_address=None)
        client = distributed.Client(cluster)

        def close():
            client.close()
            cluster.close()

        return client, close
    if isinstance(client, str):
        client = distributed.Client(client)
        return client, client.close  # our connection, not the remote cluster
    return client, lambda: None


def _default_workers(n_tasks, threads):
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    return max(1, min(n_tasks, (cores or 1) // max(1, threads)))


def _named_logs(logs):
    """(name, mote.replay keywords) for each log entry."""
    entries = logs.items() if isinstance(logs, Mapping) else ((None, e) for e in logs)
    named = []
    for name, entry in entries:
        if not isinstance(entry, Mapping):
            raise TypeError(f"sweep: a log is a dict of mote.replay keywords, not {entry!r}")
        kwargs = {k: v for k, v in entry.items() if k != "name"}
        unknown = sorted(set(kwargs) - set(LOG_KEYS))
        if unknown or "map" not in kwargs or "log" not in kwargs:
            raise ValueError(f"sweep: log {entry!r} needs 'map' and 'log' and may have "
                             f"{', '.join(LOG_KEYS[2:])} and 'name'" +
                             (f"; unknown: {', '.join(unknown)}" if unknown else ""))
        if name is None:
            name = entry.get("name", os.fspath(kwargs["log"]))
        # Absolute: a worker's working directory need not be the client's.
        kwargs = {k: (os.path.abspath(v) if k in ("map", "log", "reference") else v)
                  for k, v in kwargs.items()}
        named.append((str(name), kwargs))
    return _unique(named, "log")


def _named_configs(configs):
    """(name, LocalizerConfig fields as plain values) for each config entry."""
    if isinstance(configs, Mapping):
        entries = [(str(name), c) for name, c in configs.items()]
    else:
        entries = [(None, c) for c in configs]
    named = []
    for name, c in entries:
        config = _as_config(c)
        named.append((_config_name(c, config) if name is None else name, _fields(config)))
    return _unique(named, "config")


def _as_config(c):
    import mote

    if c is None:
        return mote.LocalizerConfig()
    if isinstance(c, mote.LocalizerConfig):
        return c
    if isinstance(c, Mapping):
        return mote.LocalizerConfig(**c)
    if isinstance(c, (str, os.PathLike)):
        return mote.load_config(os.fspath(c))
    raise TypeError(f"sweep: a config is a path, a dict of fields, a LocalizerConfig or None, "
                    f"not {c!r}")


def _fields(config):
    """The config's fields as a dict (pickles, unlike the C++ LocalizerConfig; enums do)."""
    return {name: getattr(config, name) for name in config.fields}


def _config_name(c, config):
    """A path names itself; otherwise the fields that differ from mote's defaults."""
    if isinstance(c, (str, os.PathLike)):
        return os.fspath(c)
    base, mine = _fields(type(config)()), _fields(config)
    changed = [f"{k}={_short(v)}" for k, v in mine.items() if v != base[k]]
    return ",".join(changed) or "defaults"


def _short(value):
    return value.name if hasattr(value, "__members__") else repr(value)  # BEAM, not <LaserModel..>


def _unique(named, what):
    seen = set()
    for name, _ in named:
        if name in seen:
            raise ValueError(f"sweep: two {what}s named {name!r}; give them names with a mapping "
                             f"{{name: {what}}}")
        seen.add(name)
    return named
