"""The web editor's server: a FastAPI app with a JSON API over homesim and the built editor.

Glossary:
    app: `create_app()` builds it; ``homesim serve`` runs it with uvicorn on loopback.
    API: ``/api/homes``, ``/api/actions``, ``/api/homes/{home}/objects``, ``/api/validate``,
        ``/api/execute`` and ``/api/render`` (key frames, when `homesim.render` is there).
    editor: the Blockly front end built from ``web/`` into ``homesim/serve/static``.

Needs the ``serve`` extra (``pip install homesim[serve]``).
"""

from homesim.serve.app import create_app

__all__ = ["create_app"]
