"""The VirtualHome Activity video data set: randomised episodes rendered with ground truth
into WebDataset shards, resumable, scaled out on Ray, streamed by a PyTorch loader.

Glossary:
    episode: one program animated once in one randomised home (`EpisodeSpec`): a WebDataset
        sample ``ep-NNNNNN`` with its video, per-frame maps, arrays and json.
    shard: a tar of consecutive episodes (``shards/shard-NNNNNN.tar``).
    manifest: ``episodes.parquet``, one row per episode (status, reason, checksum...).
    clip: a fixed-length window of an episode (default 2 s) with its step labels.
    profile: what episodes keep (image size, frame rate, modalities): ``full`` or ``learn``,
        the video models' format (`PROFILES`, ``--profile``).
"""

from typing import Any

from homesim.dataset.spec import PROFILES, DatasetConfig, EpisodeSpec

__all__ = ["PROFILES", "DatasetConfig", "EpisodeSpec", "Summary", "generate_dataset",
           "replay_episode"]


def __getattr__(name: str) -> Any:
    """Generation needs the renderer; reading a data set (learning) does not, so it is
    imported when first asked for."""
    if name in ("Summary", "generate_dataset", "replay_episode"):
        from homesim.dataset import generate

        return getattr(generate, name)
    raise AttributeError(f"module 'homesim.dataset' has no attribute {name!r}")
