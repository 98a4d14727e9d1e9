"""The manifest: one Parquet row per episode (key, status and reason, home made in and home
drawn, agent, seeds, frames, steps, bytes per modality, checksum), read by any Parquet
tool."""

from __future__ import annotations

import io
from pathlib import Path
from typing import Any

from homesim.errors import DataError
from homesim.files import write_bytes

MODALITY_COLUMNS = ("bytes_class", "bytes_depth", "bytes_flow", "bytes_instance",
                    "bytes_json", "bytes_pose", "bytes_rgb")


def write_manifest(rows: list[dict[str, Any]], path: Path) -> None:
    """Write the rows (every row gets every column) as Parquet, atomically."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    full = [{**{c: 0 for c in MODALITY_COLUMNS}, **r} for r in rows]
    table = pa.Table.from_pylist(full, schema=_schema(pa))
    buf = io.BytesIO()
    pq.write_table(table, buf, compression="zstd")
    write_bytes(path, buf.getvalue())


def read_manifest(path: str | Path) -> list[dict[str, Any]]:
    """The rows of a manifest, in episode order."""
    import pyarrow.parquet as pq

    try:
        return list(pq.read_table(path).to_pylist())
    except (OSError, ValueError) as e:
        raise DataError(f"{path}: cannot read the manifest ({e})") from None


def _schema(pa: Any) -> Any:
    text, i64 = pa.string(), pa.int64()
    return pa.schema([
        ("key", text), ("index", i64), ("status", text), ("stage", text), ("reason", text),
        ("program_id", text), ("home", text), ("drawn_home", text), ("agent", text),
        ("speed", pa.float64()),
        ("render_seed", i64), ("ground_seed", i64), ("placement_seed", i64), ("moves", i64),
        ("num_frames", i64), ("num_steps", i64), ("sha256", text), ("bytes", i64),
        *[(c, i64) for c in MODALITY_COLUMNS]])
