"""A user's own files given as notebook parameters (not ``--data`` TOML files): resolved to
absolute paths and hashed, so that a run's key changes when their bytes do."""

from __future__ import annotations

import hashlib
from pathlib import Path

from sss_locus import paths
from sss_locus.pipeline import provenance


def observation_parameters(path: str) -> dict[str, str]:
    """A notebook's ``observations`` file (a user's sightings CSV or XTF matches file) as an
    absolute path (relative to the current directory, else to the repository, where the worked
    example lives) and ``observations_sha256``, the hash of its bytes and of the XTF files it
    names: an edited file makes the run stale, as an edited ``--data`` file does."""
    from sss_locus.experiments.observations_xtf import observation_files

    given = Path(str(path)).expanduser()
    found = next((p for p in (given, paths.REPO_ROOT / given) if p.is_file()), given)
    found = found.resolve() if found.is_file() else given
    digest = hashlib.sha256()
    for f in observation_files(found):
        digest.update(provenance.file_sha256(f).encode())
    return {"observations": str(found), "observations_sha256": digest.hexdigest()}
