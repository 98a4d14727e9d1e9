"""The web editor's server: a FastAPI app with a JSON API over homesim and the built editor.

Glossary:
    app: `create_app()` builds it; ``homesim serve`` runs it with uvicorn on loopback
        (`server.uvicorn_config`: header, body, keep-alive and shutdown deadlines).
    API: ``/api/homes``, ``/api/actions``, ``/api/homes/{home}/objects``, ``/api/validate``,
        ``/api/execute`` and ``/api/render`` (render jobs: `renders`).
    workers: processes for render jobs and large programs (`workers`, `renders`), so the
        event loop and the thread pool stay free for small requests.
    hosts: the Host names served (`hosts`, against DNS rebinding).
    editor: the Blockly front end built from ``web/`` into ``homesim/serve/static``.

Needs the ``serve`` extra (``pip install homesim[serve]``).
"""

from homesim.serve.app import create_app

__all__ = ["create_app"]
