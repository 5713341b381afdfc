"""Bad input stops the study layer with one line that names the file and the field."""
import json


class StudyError(Exception):
    """A study, config or result file the study layer cannot use; the message names the file and the field.
    __main__ prints it as one line and exits 2."""


def fail(message):
    raise StudyError(message)


def load_json(path, what):
    """The JSON in path; `what` names the file in the error (\"study\", \"verification\", ...)."""
    try:
        with open(path) as f:
            return json.load(f)
    except OSError as e:
        fail(f"{path}: cannot open {what} ({e.strerror})")
    except ValueError as e:
        fail(f"{path}: not valid JSON ({e})")
