"""Bad input stops the study layer with one line per problem, each naming the file or option and the field."""
import json


class StudyError(Exception):
    """A study, config or result file the study layer cannot use; the message names the file and the field.
    __main__ prints it as one line and exits 2."""


class StudyErrors(StudyError):
    """Several problems of one command, found together before anything was written: __main__ prints one line per
    problem and exits 2."""

    def __init__(self, messages):
        self.messages = [str(m).replace("\n", " ") for m in messages]
        super().__init__("\n".join(self.messages))


def fail(message):
    raise StudyError(message)


def messages_of(error):
    """The lines a StudyError prints: one per problem."""
    if isinstance(error, StudyErrors):
        return list(error.messages)
    return [str(error).replace("\n", " ")]


class Problems:
    """Collects every problem of a command before it writes anything, so that all of them are reported in one go
    (one line each) rather than one per try."""

    def __init__(self):
        self.messages = []

    def add(self, message):
        if message not in self.messages:
            self.messages.append(message)

    def check(self, function, *args, **kwargs):
        """function(*args, **kwargs), or None with its StudyError(s) noted as problems."""
        try:
            return function(*args, **kwargs)
        except StudyError as e:
            for m in messages_of(e):
                self.add(m)
            return None

    def __bool__(self):
        return bool(self.messages)

    def raise_if_any(self):
        if self.messages:
            raise StudyErrors(self.messages)


def load_json(path, what):
    """The JSON in path; `what` names the file in the error (\"study\", \"verification\", ...)."""
    try:
        with open(path) as f:
            return json.load(f)
    except OSError as e:
        fail(f"{path}: cannot open {what} ({e.strerror})")
    except ValueError as e:
        fail(f"{path}: not valid JSON ({e})")
