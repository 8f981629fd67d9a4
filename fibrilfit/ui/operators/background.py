"""A sidebar operator over a job on a thread (search/background.py: Minimal linker… and
Report…): started, then polled by a window timer so Blender stays live, its progress in the
status bar, Esc stops it (the workers killed, nothing kept), and finish() puts its result in the
panel. Called from a script or in the background (no event loop), it waits for the job instead.
Subclasses define make_job() (the job, started), progress_text() and finish()."""
import bpy

from . import common, simulate

POLL_SECONDS = 0.25
RUNNING = {}  # bl_idname -> the job under way: one of each at a time (poll reads it)


class BackgroundOperator:
    """The modal part of an operator whose job runs on a thread (search/background.py)."""

    what = ""  # the job's name in the status bar ("minimal linker", "report")
    job_name = ""  # and in "A ... is running"
    _job = None
    _timer = None
    _cancelling = False

    @classmethod
    def running(cls, context) -> bool:
        """poll()'s part: False (and why) while a job of this operator runs."""
        job = RUNNING.get(cls.bl_idname)
        if job is not None and not job.finished:
            cls.poll_message_set(f"A {cls.job_name} is running: Esc stops it")
            return True
        return False

    def execute(self, context):
        return common.guarded(self, self._execute, context)

    def start(self, context) -> None:
        """The job made (checked) and started on its thread."""
        self._job = self.make_job(context)
        RUNNING[self.bl_idname] = self._job
        self._cancelling = False

    def _execute(self, context):
        self.start(context)
        if bpy.app.background or context.window is None:  # no event loop: wait here
            self._job.join()
            return self.ended(context)
        wm = context.window_manager
        self._timer = wm.event_timer_add(POLL_SECONDS, window=context.window)
        wm.modal_handler_add(self)
        self.show_progress(context)
        return {"RUNNING_MODAL"}

    def modal(self, context, event):
        return common.guarded(self, self._modal, context, event)

    def _modal(self, context, event):
        if event.type == "ESC" and not self._cancelling:
            self._job.stop()
            self._cancelling = True
            self.show_progress(context)
            return {"RUNNING_MODAL"}
        if event.type == "TIMER":
            if self._job.finished:
                return self.ended(context)
            self.show_progress(context)
        # the scene is not the job's (the workers have their own): the user goes on working
        return {"PASS_THROUGH"}

    def show_progress(self, context) -> None:
        if self._cancelling:
            simulate._status(context, f"FibrilFit: {self.what}: cancelling…")
        else:
            text, fraction = self.progress_text(self._job.progress)
            simulate._status(context, f"FibrilFit: {self.what}: {text} (Esc to cancel)",
                             fraction)

    def end(self, context) -> None:
        if self._timer is not None:
            context.window_manager.event_timer_remove(self._timer)
            self._timer = None
        simulate._status(context, None)
        if RUNNING.get(self.bl_idname) is self._job:
            RUNNING[self.bl_idname] = None

    def ended(self, context) -> set:
        """The job has ended: the timer and status bar cleared, then finish()."""
        self.end(context)
        return self.finish(context)

    def cancel(self, context):
        """Blender ends the operator (a file loaded, the window closed): stop the job."""
        if self._job is not None and not self._job.finished:
            self._job.stop()
        self.end(context)
        self.discard()

    def discard(self) -> None:
        """What a stopped job leaves, removed (nothing by default)."""
