"""The plans the shell keeps, per scene: fingerprint -> Part (:func:`toolpath.job.plan_job`'s
cache), so Export writes what Generate planned when nothing changed and re-plans only what did.
Shell state (the core keeps none): it lives as long as the Blender session."""
from __future__ import annotations

KEEP = 32            # parts kept per scene besides those of the last plan (each edit makes new ones)

_CACHES: dict = {}   # scene.session_uid -> {fingerprint: Part}, oldest first


def cache_of(scene) -> dict:
    return _CACHES.setdefault(scene.session_uid, {})


def keep(cache: dict, planned) -> None:
    """Keep in ``cache`` (a scene's, :func:`cache_of`) the parts of ``planned`` (a PlannedJob) and
    the most recent others, up to :data:`KEEP`."""
    used = {item.fingerprint for item in planned.planned}
    others = [key for key in cache if key not in used]
    for key in others[:max(0, len(others) - KEEP)]:
        del cache[key]


def replanned_message(names: list) -> str:
    """What an Export says of the plan it wrote: the operations it planned again, or none (the
    program as Generate planned it)."""
    return f"re-planned: {', '.join(names)}" if names else "nothing re-planned"
