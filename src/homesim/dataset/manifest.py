"""The manifest: one Parquet row per episode (key, status and reason, home made in and home
drawn, agent, seeds, frames, steps, bytes per modality, checksum), read by any Parquet
tool."""

from __future__ import annotations

import io
from pathlib import Path
from typing import Any

from homesim.errors import DataError, HomesimError, one_line
from homesim.files import read_limited, write_bytes
from homesim.limits import MAX_DATA_FILE_BYTES

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
    """The rows of a manifest, in episode order; `DataError` naming the file and why when
    it is not a regular file (links not followed), over `MAX_DATA_FILE_BYTES` or not a
    Parquet table of rows."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    try:
        data = read_limited(path, MAX_DATA_FILE_BYTES, "MAX_DATA_FILE_BYTES", "manifest",
                            follow_links=False)
        rows = pq.read_table(pa.BufferReader(data)).to_pylist()
    except HomesimError as e:
        raise DataError(str(e)) from None
    except (OSError, ValueError, pa.ArrowException) as e:
        raise DataError(f"{path}: cannot read the manifest "
                        f"({one_line(str(e) or type(e).__name__, 120)})") from None
    return [r if isinstance(r, dict) else {} for r in rows]


def _schema(pa: Any) -> Any:
    text, i64 = pa.string(), pa.int64()
    return pa.schema([
        ("key", text), ("index", i64), ("status", text), ("stage", text), ("reason", text),
        ("program_id", text), ("home", text), ("drawn_home", text), ("agent", text),
        ("speed", pa.float64()),
        ("render_seed", i64), ("ground_seed", i64), ("placement_seed", i64), ("moves", i64),
        ("num_frames", i64), ("num_steps", i64), ("sha256", text), ("bytes", i64),
        *[(c, i64) for c in MODALITY_COLUMNS]])
