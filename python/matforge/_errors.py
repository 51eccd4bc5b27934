"""The exceptions matforge raises. Each carries a `code`: the finding code where one applies
(docs/interface.md, "Finding codes"), else the kind of failure ("usage", "INTERRUPTED", ...)."""

from __future__ import annotations


class Error(Exception):
    """Anything matforge refuses or cannot do; `code` says which kind."""

    def __init__(self, message: str, code: str) -> None:
        super().__init__(message)
        self.message = message
        self.code = code


class UsageError(Error):
    """A bad argument or configuration: unknown preset, invalid rules, an output folder that is or
    holds an input (what `matforge` exits 2 for). code: "usage"."""


class InputError(Error):
    """No input could be read at all (a typo'd folder): code "INPUT_NOT_FOUND"."""


class OutputError(Error):
    """The output folder, an output or the manifest could not be written, or another ingest holds
    the folder's lock: code "OUTPUT_WRITE_FAILED"."""


class ManifestError(Error):
    """A manifest that cannot be read or is not one this version reads: code "manifest"."""


class MergeError(Error):
    """merge() refused: a shard's run failed (the message names each part and its first failure);
    run those shards again, or merge with keep_errors=True. code: "shard_failed"."""


class Cancelled(Error):
    """The run stopped early, asked to (a Cancel token, a progress callback returning False), as
    `matforge ingest` stops on SIGINT: every file written is complete, no temporary is left, and no
    manifest is written. Run it again to finish. code: "INTERRUPTED"."""
