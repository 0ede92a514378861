"""The workbench: draw a mechanism in the browser, watch it move, design it, save it (``gearlever workbench``).

A local web application on the library's engine.  The server (Python) answers
a whole cycle of frames per edit; the page (plain JavaScript modules in
``static/``) plays and scrubs without a round trip.

- :mod:`~gearlever.workbench.engine`: pure functions the routes call (parse,
  dump, solve, structure, forces, export, synthesis jobs); no web imports.
- :mod:`~gearlever.workbench.app`: the Starlette application
  (:func:`~gearlever.workbench.app.create_app`): token, Host check, caps,
  JSON errors, the OpenAPI document at ``/api/openapi.json``.
- :mod:`~gearlever.workbench.jobs`: one synthesis job at a time, progress as
  server-sent events, cancel.
- :mod:`~gearlever.workbench.files`: the workspace folder (names inside it
  only, ETag, atomic writes, ``If-Match``).
- :mod:`~gearlever.workbench.serve`: uvicorn on a free loopback port, the
  printed URL, signals.

This package may import the library, Starlette and uvicorn; the library never
imports it.

Agreement between the server and the page:

- The URL printed is ``http://HOST:PORT/?token=TOKEN``; when the command is
  given a model file, the URL also carries ``&open=NAME`` (NAME the file's
  name relative to the workspace, which is then the file's folder) and the
  page fetches it with ``GET /api/files/NAME`` (keeping its ETag for the save).
- ``GET /?token=TOKEN`` with the right token sets the cookie
  ``gearlever_token`` (HttpOnly, SameSite=Strict, Path=/); every other route
  accepts that cookie, ``Authorization: Bearer TOKEN`` or ``?token=TOKEN``.
  Static files under ``/static/`` thus load with the cookie alone.
"""
