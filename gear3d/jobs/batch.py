"""Part libraries: a part template swept over parameters, built in parallel, with a
manifest and resume.

* Engines: a local process pool (``workers`` processes, forkserver start so that no
  manifold/TBB thread state is forked; ``workers=0`` runs in this process) or Dask
  distributed (``engine="dask"``, the ``gear3d[dask]`` extra: a ``LocalCluster`` when no
  ``scheduler`` address is given, else that cluster; its workers must see ``out_dir`` and
  import gear3d). Workers write the part's files themselves (atomically) and return plain
  dict records (arrays/paths/numbers, never manifold objects).
* Cheap workers: parts go out in chunks (:func:`chunked`: about 8 chunks per worker, at
  most :data:`CHUNK_MAX` parts each), so one task carries several parts; the forkserver
  preloads the modules the library's outputs need (:func:`worker_modules`, nothing more:
  an STL library never imports trimesh, ezdxf or matplotlib there), so each worker starts
  by a fork, not by re-importing.
* Orphans: every pool worker watches a pipe whose only write end this process holds
  (:func:`_watch_parent`); when this process dies, even by SIGKILL, the pipe reads EOF and
  the worker exits at once, which in turn lets the forkserver and the resource tracker
  exit. A part in flight may still land (atomically, complete), no new one starts.
* Each finished part leaves a record ``out_dir/.records/<name>.json`` (written after its
  files). ``manifest.json`` / ``manifest.csv`` are assembled from the records in library
  order: per part its parameters, files with sha256, volume, triangles and measured max
  errors, or its error. Wall-clock times go to ``timings.json`` only, so a batch killed
  (SIGINT/SIGKILL) and re-run ends with byte-identical manifests, whichever engine or
  worker count built it.
* Resume: a part whose record matches its spec and whose files still hash as recorded
  is skipped. A failed part records its error and the batch goes on (it is retried on a
  re-run).
* Refusals before any file: a bad value, an output folder that cannot be written, Dask
  not installed (``pip install 'gear3d[dask]'``) or a scheduler that does not answer
  raise :class:`~gear3d.errors.GearError` before the folder is created.
"""
from __future__ import annotations

import csv
import io
import json
import logging
import os
import sys
import time

from ..budget import limits, worker_limits
from ..errors import GearError, check_choice, check_number
from .graph import Graph, canonical
from .scene import part_targets, profile_stage, body_stage, sha256, write_json
from .specs import Job, Library, LibraryPart
from .template import MESH_KINDS
from ..export import FORMATS
from ..filesafe import LIVE_TEMPS, atomic_path, check_out_dir, file_event, make_out_dir
from ..profiles import FAMILY_MODULES

RECORDS = ".records"


def job_header(lib: Library) -> Job:
    """The picklable part of a library every worker needs (:meth:`Job.header`)."""
    return lib.header()


def spec_of(job: Job, part: LibraryPart) -> str:
    """A hash of everything that decides a part's files (resume compares it)."""
    import hashlib
    d = {"family": part.family, "params": part.params, "body": part.body,
         "outputs": {k: job.tolerance_for(k) for k in part.outputs}, "options": job.options}
    return hashlib.sha256(canonical(d).encode()).hexdigest()[:20]


def build_part(job: Job, part: LibraryPart, out_dir: str) -> dict:
    """Build one library part (in a worker): its files, then its record. Returns
    ``{"record": ..., "seconds": wall s, "cpu_seconds": this process's CPU s, "stages": {...},
    "worker": "host:pid", ...}``; errors are recorded, not raised."""
    t0, c0 = time.perf_counter(), time.process_time()
    g = Graph()
    rec = {"name": part.name, "values": part.values, "family": part.family,
           "params": part.params, "body": part.body, "spec": spec_of(job, part)}
    try:
        targets = part_targets(g, job, part, out_dir, prefix=f"part {part.name}")
        with limits(**worker_limits()):       # each part is a job of its own, under the run's limits
            res = g.run(list(targets.values()))
        files, errs = [], {}
        for kind, key in targets.items():
            info = res[key]
            files.append({"kind": kind, "file": info["file"], "sha256": info["sha256"], "bytes": info["bytes"]})
            if "max_error" in info:
                errs[kind] = info["max_error"]
        profs = [r for k, r in g.results.items() if g.stages[k].kind == "profile"]
        bodies = [r for k, r in g.results.items() if g.stages[k].kind == "body"]
        rec.update(status="ok", error=None, files=files,
                   volume=bodies[0].report["volume"] if bodies else None,
                   triangles=bodies[0].report["triangles"] if bodies else None,
                   max_error={"profile": max(p.report["max_error"] for p in profs) if profs else None,
                              "body": max(b.report["max_error"] for b in bodies) if bodies else None,
                              **errs})
    except Exception as e:  # noqa: BLE001 -- a failed part is recorded, the batch goes on
        rec.update(status="failed", error=f"{type(e).__name__}: {e}", files=[], volume=None,
                   triangles=None, max_error=None)
    rec = write_record(out_dir, part.name, rec)
    return {"record": rec, "seconds": time.perf_counter() - t0,
            "cpu_seconds": time.process_time() - c0, "stages": dict(g.counts),
            "cache_hits": dict(g.cache_hits), "worker": worker_id(),
            "heavy_imports": [m for m in HEAVY_MODULES if m in sys.modules]}


#: libraries a worker should import only when an output needs them (seconds each)
HEAVY_MODULES = ("trimesh", "scipy", "shapely", "matplotlib", "ezdxf", "lxml")


_HOST = []


def worker_id() -> str:
    """``host:pid`` of the process building a part (timings.json counts parts per worker)."""
    if not _HOST:
        import socket
        _HOST.append(socket.gethostname())
    return f"{_HOST[0]}:{os.getpid()}"


def write_record(out_dir, name: str, rec: dict) -> dict:
    """Write part ``name``'s record to ``out_dir/.records/NAME.json`` (strict JSON, the bytes
    of :func:`gear3d.jobs.scene.write_json`) and return it cleaned.

    Atomic as every file here (a temporary file renamed into place; a kill leaves at most
    ``.NAME.json.PID.tmp``, removed by the next run; both announced as file events, see
    :func:`gear3d.filesafe.file_event`), but without the destination probe of
    :func:`gear3d.filesafe.atomic_path`: the folder was checked when the batch started, and a
    probe costs two more file creations a part."""
    clean = _jsonable(rec)
    text = json.dumps(clean, indent=1, allow_nan=False) + "\n"
    folder = os.path.join(out_dir, RECORDS)
    path, tmp = os.path.join(folder, name + ".json"), os.path.join(folder, f".{name}.json.{os.getpid()}.tmp")
    LIVE_TEMPS.add(tmp)
    try:
        try:
            f = open(tmp, "w", encoding="utf-8")
        except FileNotFoundError:
            os.makedirs(folder, exist_ok=True)
            f = open(tmp, "w", encoding="utf-8")
        file_event("tmp", tmp)
        with f:
            f.write(text)
        os.replace(tmp, path)
        file_event("done", path)
    finally:
        if os.path.lexists(tmp):
            os.remove(tmp)
        LIVE_TEMPS.discard(tmp)
    return clean


def _jsonable(rec):
    from ..export.json_format import clean
    return clean(rec)


def _done_record(out_dir, part, spec):
    """The stored record of a complete part (files present with their hashes), else None."""
    p = os.path.join(out_dir, RECORDS, part.name + ".json")
    try:
        with open(p, encoding="utf-8") as f:
            rec = json.load(f)
    except (OSError, ValueError):
        return None
    if rec.get("spec") != spec or rec.get("status") != "ok":
        return None
    for fi in rec.get("files", []):
        fp = os.path.join(out_dir, fi["file"])
        if not os.path.isfile(fp) or sha256(fp) != fi["sha256"]:
            return None
    return rec


def _clean_stale(out_dir, lib):
    """Remove temporary files a killed run left behind (only this library's names)."""
    names = {p.name + "." + k for p in lib.parts for k in p.outputs}
    names |= {"manifest.json", "manifest.csv", "timings.json"}
    recs = {p.name + ".json" for p in lib.parts}
    for folder, known in ((out_dir, names), (os.path.join(out_dir, RECORDS), recs)):
        if not os.path.isdir(folder):
            continue
        for f in os.listdir(folder):
            if f.startswith(".") and ".tmp" in f and any(f.startswith("." + n + ".") for n in known):
                os.remove(os.path.join(folder, f))


def preflight(lib: Library):
    """Build the first part's profile (and body, when a mesh output needs it) in memory so
    that a bad value that is not swept stops the batch with exit 2 before any file."""
    if not lib.parts:
        return
    part = lib.parts[0]
    swept = {k.split(".")[-1] for k in part.values}
    g = Graph()
    targets = []
    for kind in part.outputs:
        tol = lib.tolerance_for(kind)
        if kind in MESH_KINDS and part.body is not None:
            targets.append(body_stage(g, lib, part, tol, "library.part"))
        else:
            targets.append(profile_stage(g, lib, part, tol, "library.part"))
    try:
        g.run(targets)
    except GearError as e:
        p = getattr(e, "key", "") or ""
        leaf = p.rsplit(".", 1)[-1].split(" ")[0]
        if leaf not in swept and not any(s in p for s in swept):
            raise


#: most parts in one worker task (a chunk): fewer round trips, a bounded loss on interrupt
CHUNK_MAX = 8
#: chunks per worker aimed at (load balance against per-task overhead)
CHUNKS_PER_WORKER = 8
#: seconds to wait for a Dask scheduler to answer
CONNECT_TIMEOUT_S = 20.0
DASK_HINT = "pip install 'gear3d[dask]'"


def require_dask():
    """Import ``dask.distributed`` or refuse: GearError naming the extra to install."""
    try:
        import dask.distributed  # noqa: F401
    except ImportError:
        raise GearError("engine", "dask", f"local, or dask after: {DASK_HINT}",
                        "Dask is not installed") from None


def chunked(todo: list, workers: int) -> list:
    """Split ``todo`` into consecutive chunks: about :data:`CHUNKS_PER_WORKER` per worker,
    each of 1 to :data:`CHUNK_MAX` parts."""
    size = max(1, min(CHUNK_MAX, len(todo) // (CHUNKS_PER_WORKER * max(workers, 1))))
    return [todo[i:i + size] for i in range(0, len(todo), size)]


#: in a pool worker: set by the batch process when it is interrupted (stop between parts)
_STOP = None


def build_chunk(job: Job, parts: list, out_dir: str) -> list:
    """Build several parts in one task (see :func:`build_part`); returns their results.
    In a pool worker the chunk ends early, between two parts, once the batch process
    asks it to stop (an interrupt): the parts not built are built by the next run."""
    out = []
    for p in parts:
        if _STOP is not None and _STOP.is_set():
            break
        out.append(build_part(job, p, out_dir))
    return out


def worker_modules(lib: Library) -> list:
    """The modules a worker needs for this library's outputs (the forkserver preloads
    them once): the batch and stage code, the family registry, manifold3d and the solids
    for mesh outputs, and each output's exporter module."""
    from .scene import EXT
    kinds = {k for p in lib.parts for k in p.outputs}
    mods = ["numpy", "gear3d.jobs.batch", "gear3d.jobs.scene", "gear3d.export", "gear3d.export.json_format"]
    mods += [f"gear3d.profiles.{m}" for m in FAMILY_MODULES]
    if kinds & set(MESH_KINDS) and any(p.body is not None for p in lib.parts):
        # gear3d.solids loads its names on first use: the builders by name
        mods += ["manifold3d", "gear3d.solids", "gear3d.solids.body", "gear3d.exact"]
    for k in sorted(kinds):
        fmt = FORMATS.get(EXT[k])
        if fmt is not None:
            mods.append(fmt.module_name)
    return list(dict.fromkeys(mods))


def _watch_parent(conn, stop=None):
    """Pool worker initializer: exit as soon as the batch process is gone.

    ``conn`` is the read end of a pipe whose only write end the batch process holds and
    never writes to: ``recv_bytes`` blocks until that process exits (EOF), however it dies.
    A daemon thread waits on it and ends this worker with ``os._exit``. ``stop`` (an
    Event) is kept for :func:`build_chunk`."""
    import threading
    global _STOP
    _STOP = stop

    def watch():
        try:
            conn.recv_bytes()
        except (EOFError, OSError):
            pass
        os._exit(70)

    threading.Thread(target=watch, name="gear3d-parent-watch", daemon=True).start()


def run_library(lib: Library, out_dir, workers: int = 2, engine: str = "local", scheduler=None,
                processes: bool = True, progress: bool = True) -> dict:
    """Build a validated library (:func:`gear3d.jobs.template.load_library`) into ``out_dir``.

    Returns ``{"manifest": ..., "built": n, "skipped": n, "failed": n, "seconds": s,
    "parts_per_s": r}``. ``engine``: local | dask; ``workers``: processes (local, 0 = in
    this process) or Dask workers of a LocalCluster (``processes`` picks process or thread
    workers); ``scheduler``: an existing Dask scheduler address (``tcp://HOST:PORT``).
    Bad input, a library over the budget (its parts still to build, planned whole:
    :func:`gear3d.plan_jobs.plan_library`), an unwritable ``out_dir``, Dask missing or an
    unreachable scheduler raise GearError before anything is written.

    >>> import tempfile
    >>> from gear3d.jobs.template import load_library
    >>> lib = load_library("templates/sine-spur-library.toml")      # from the repository's root
    >>> r = run_library(lib, tempfile.mkdtemp(), workers=0, progress=False)
    >>> r["built"], r["failed"]
    (51, 0)
    """
    engine, workers = _checked_engine(engine, workers, scheduler)
    out_dir, job = str(out_dir), job_header(lib)
    records, todo = _resume_scan(lib, job, out_dir)
    from ..plan_jobs import plan_library
    plan_library(job, todo, out_dir, part_targets, workers)      # the whole batch, before its first part
    preflight(lib)
    check_out_dir(out_dir, "out")
    runner = _open_runner(lib, todo, out_dir, engine, workers, scheduler, processes)
    run = _BatchRun(lib, out_dir, records, progress)
    try:
        if runner is not None:
            runner.run(job, chunked(todo, runner.slots), out_dir, run.done)
        else:
            for part in todo:
                run.done(build_part(job, part, out_dir))
    finally:
        run.finish(runner, job, todo, engine, workers)
    return run.result()


def _checked_engine(engine, workers, scheduler) -> tuple:
    """(engine, workers) checked; Dask imported when asked for (GearError otherwise)."""
    engine = check_choice("engine", engine, ("local", "dask"))
    workers = check_number("workers", workers, 0, 1024, integer=True)
    if scheduler is not None and engine != "dask":
        raise GearError("scheduler", scheduler, "only with engine dask")
    if engine == "dask":
        require_dask()
    return engine, workers


def _resume_scan(lib: Library, job: Job, out_dir: str) -> tuple:
    """({name: record} of the parts already complete in ``out_dir``, [parts to build])."""
    records, todo = {}, []
    try:
        stored = set(os.listdir(os.path.join(out_dir, RECORDS)))
    except OSError:
        stored = set()
    for part in lib.parts:
        rec = _done_record(out_dir, part, spec_of(job, part)) if part.name + ".json" in stored else None
        if rec is not None:
            records[part.name] = rec
        else:
            todo.append(part)
    return records, todo


def _open_runner(lib, todo, out_dir, engine, workers, scheduler, processes):
    """The engine's runner (None: this process builds), started before the output folder
    is made (a Dask scheduler that does not answer leaves no folder); then the folder."""
    runner = None
    if todo and engine == "dask":
        runner = _DaskRunner(workers, scheduler, processes)     # connects before any file
    elif todo and workers > 0:
        runner = _PoolRunner(workers, worker_modules(lib))
    try:
        make_out_dir(out_dir, "out")       # then a manifest is always written into it
    except BaseException:
        if runner is not None:
            runner.close()
        raise
    _clean_stale(out_dir, lib)
    return runner


class _BatchRun:
    """One run of a library: the records as parts finish, the progress bar, the partial
    manifests, and at the end the manifest, ``timings.json`` and the summary."""

    def __init__(self, lib: Library, out_dir: str, records: dict, progress: bool):
        self.lib, self.out_dir, self.records = lib, out_dir, records
        self.skipped, self.failed = len(records), 0
        self.timings = _read_timings(out_dir)
        self.t0 = self.last_manifest = time.perf_counter()
        self.bar = _bar(len(lib.parts), self.skipped, progress)
        self.used, self.heavy, self.cpu = {}, set(), 0.0
        self.manifest, self.dt = None, 0.0

    def done(self, res: dict) -> None:
        """A part's result (:func:`build_part`) is in: record it, count it, show it."""
        rec = res["record"]
        self.records[rec["name"]] = rec
        self.timings["parts"][rec["name"]] = round(res["seconds"], 4)
        self.used[res["worker"]] = self.used.get(res["worker"], 0) + 1
        self.cpu += res.get("cpu_seconds", 0.0)
        self.heavy.update(res["heavy_imports"])
        if rec["status"] != "ok":
            self.failed += 1
        if self.bar is not None:
            self.bar.update(1)
            self.bar.set_postfix(done=len(self.records), failed=self.failed, refresh=False)
        if time.perf_counter() - self.last_manifest > 5.0:   # a partial manifest now and then
            _write_manifest(self.out_dir, self.lib, self.records)
            self.last_manifest = time.perf_counter()

    def finish(self, runner, job: Job, todo: list, engine: str, workers: int) -> None:
        """Close the runner, pick up parts whose result never came back, write the manifest
        and the timings."""
        if runner is not None:
            runner.close()
            # parts finished in a worker whose result never came back (an interrupt): their
            # records are on disk, so the manifest lists every complete part
            for part in todo:
                if part.name not in self.records:
                    rec = _done_record(self.out_dir, part, spec_of(job, part))
                    if rec is not None:
                        self.records[part.name] = rec
        if self.bar is not None:
            self.bar.close()
        self.manifest = _write_manifest(self.out_dir, self.lib, self.records)
        dt = self.dt = time.perf_counter() - self.t0
        built = len(self.records) - self.skipped
        self.timings.update(engine=engine, workers=workers, last_run_seconds=round(dt, 3),
                            last_run_built=built, last_run_parts_per_s=round(built / dt, 3) if dt > 0 else None,
                            last_run_workers=dict(sorted(self.used.items())),
                            last_run_heavy_imports=sorted(self.heavy), last_run_cpu_seconds=round(self.cpu, 3))
        write_json(os.path.join(self.out_dir, "timings.json"), self.timings)

    def result(self) -> dict:
        """The summary :func:`run_library` returns."""
        built, dt = len(self.records) - self.skipped, self.dt
        bad = [self.records[p.name] for p in self.lib.parts
               if p.name in self.records and self.records[p.name]["status"] != "ok"]
        return {"manifest": self.manifest, "built": built, "skipped": self.skipped, "failed": len(bad),
                "first_failure": bad[0] if bad else None,
                "seconds": dt, "parts_per_s": built / dt if dt > 0 else None}


def _bar(total, initial, progress):
    if not progress:
        return None
    from tqdm import tqdm
    return tqdm(total=total, initial=initial, unit="part", file=sys.stderr, dynamic_ncols=True,
                smoothing=0.1, bar_format="{l_bar}{bar}| {n_fmt}/{total_fmt} [{elapsed}<{remaining}, "
                "{rate_fmt}{postfix}]")


class _PoolRunner:
    """A local process pool (forkserver where available) whose workers exit when this
    process dies (:func:`_watch_parent`)."""

    def __init__(self, workers: int, modules: list):
        import multiprocessing as mp
        from concurrent.futures import ProcessPoolExecutor
        method = "forkserver" if "forkserver" in mp.get_all_start_methods() else "spawn"
        ctx = mp.get_context(method)
        if method == "forkserver":
            ctx.set_forkserver_preload(modules)
        self.workers = self.slots = workers
        # the write end stays here and is never written: EOF in a worker = this process died
        self._watch_r, self._watch_w = ctx.Pipe(duplex=False)
        self.stop = ctx.Event()
        self.ex = ProcessPoolExecutor(max_workers=workers, mp_context=ctx, initializer=_watch_parent,
                                      initargs=(self._watch_r, self.stop))

    def run(self, job, chunks, out_dir, done):
        from concurrent.futures import FIRST_COMPLETED, wait
        # a bounded window of chunks in flight, so an interrupt loses little work
        it = iter(chunks)
        pending = set()
        try:
            for ch in it:
                pending.add(self.ex.submit(build_chunk, job, ch, out_dir))
                if len(pending) >= 2 * self.workers:
                    break
            while pending:
                fin, pending = wait(pending, return_when=FIRST_COMPLETED)
                for f in fin:
                    for res in f.result():
                        done(res)
                    nxt = next(it, None)
                    if nxt is not None:
                        pending.add(self.ex.submit(build_chunk, job, nxt, out_dir))
        except BaseException:
            self.stop.set()                # running chunks end after their current part
            raise

    def close(self):
        """Cancel the queued chunks, wait for the running ones (they end after their current
        part once ``stop`` is set), then drop the pipe."""
        self.ex.shutdown(wait=True, cancel_futures=True)
        self._watch_w.close()
        self._watch_r.close()


def quiet_local_cluster():
    """Keep the LocalCluster gear3d starts (and its worker processes, which read the
    environment when they import ``distributed``) from logging below CRITICAL.

    At shutdown a worker's last heartbeat can meet a scheduler that is already closing, and
    ``distributed`` logs that as an ERROR with a traceback although every part was built: the
    batch's own summary line and exit code say what happened. A level the user has set in the
    environment (``DASK_LOGGING__DISTRIBUTED``) is kept. Parts that fail still come back as
    exceptions through their futures.
    """
    level = os.environ.setdefault("DASK_LOGGING__DISTRIBUTED", "critical")
    logging.getLogger("distributed").setLevel(level.upper())


class _DaskRunner:
    """Dask distributed: a LocalCluster, or the cluster behind ``scheduler``."""

    def __init__(self, workers, scheduler, processes):
        require_dask()
        if not scheduler:
            quiet_local_cluster()
        from dask.distributed import Client, LocalCluster
        self.cluster = None
        if scheduler:
            try:
                self.client = Client(scheduler, timeout=CONNECT_TIMEOUT_S)
            except Exception as e:  # noqa: BLE001 -- OSError, TimeoutError, ValueError (bad address)
                why = " ".join(f"{type(e).__name__}: {e}".split())[:200]
                raise GearError("scheduler", scheduler,
                                "the address of a running Dask scheduler, e.g. tcp://HOST:8786", why) from None
        else:
            self.cluster = LocalCluster(n_workers=max(workers, 1), threads_per_worker=1, processes=processes,
                                        dashboard_address=None)
            self.client = Client(self.cluster)
        # parts run one per worker thread: chunk for the threads the cluster has now
        info = self.client.scheduler_info()
        self.slots = max(1, sum(w.get("nthreads", 1) for w in info.get("workers", {}).values()) or workers)

    def run(self, job, chunks, out_dir, done):
        from dask.distributed import as_completed
        out = os.path.abspath(out_dir)
        futs = self.client.map(build_chunk, [job] * len(chunks), chunks, [out] * len(chunks), pure=False)
        try:
            for f in as_completed(futs):
                for res in f.result():
                    done(res)
        except BaseException:
            self.client.cancel(futs)
            raise

    def close(self):
        self.client.close()
        if self.cluster is not None:
            self.cluster.close()


def _read_timings(out_dir):
    try:
        with open(os.path.join(out_dir, "timings.json"), encoding="utf-8") as f:
            t = json.load(f)
        if isinstance(t.get("parts"), dict):
            return t
    except (OSError, ValueError):
        pass
    return {"parts": {}}


def _write_manifest(out_dir, lib: Library, records) -> dict:
    parts = [records[p.name] for p in lib.parts if p.name in records]
    ok = sum(1 for r in parts if r["status"] == "ok")
    manifest = {
        "library": lib.name, "file": os.path.basename(lib.file), "pattern": lib.pattern,
        "tolerance": lib.tolerance, "tolerances": lib.tolerances, "zip": lib.zip,
        "summary": {"parts": len(lib.parts), "recorded": len(parts), "ok": ok,
                    "failed": len(parts) - ok, "files": sum(len(r["files"]) for r in parts)},
        "timings": "timings.json",
        "parts": parts,
    }
    write_json(os.path.join(out_dir, "manifest.json"), manifest)
    keys = sorted({k for r in parts for k in r["values"]})
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["name", "status", "family", *keys, "params", "body", "files", "sha256", "volume_mm3",
                "triangles", "max_error_mm", "error"])
    for r in parts:
        me = r["max_error"] or {}
        w.writerow([r["name"], r["status"], r["family"], *[r["values"].get(k, "") for k in keys],
                    json.dumps(r["params"], sort_keys=True), json.dumps(r["body"], sort_keys=True),
                    " ".join(f["file"] for f in r["files"]), " ".join(f["sha256"] for f in r["files"]),
                    "" if r["volume"] is None else repr(r["volume"]),
                    "" if r["triangles"] is None else r["triangles"],
                    "" if not me else repr(max(v for v in me.values() if v is not None)),
                    r["error"] or ""])
    with atomic_path(os.path.join(out_dir, "manifest.csv")) as tmp:
        with open(tmp, "w", encoding="utf-8", newline="") as f:
            f.write(buf.getvalue())
    return manifest
