// A run through the tool controller: select the program (when another one is selected), start,
// wait for the controller to confirm it, stop, and end it with the controller's result or the
// hub's reason (not started, no result, controller lost, bus fault). The CAN frames and their
// timings are protocol::smart_tool's; every step is driven by update() with the time passed in.
#include <spdlog/spdlog.h>

#include "smart_tool_logic.h"

namespace hubrt::tool_ecu {

namespace st = protocol::smart_tool;

void SmartToolLogic::begin(const Want& want, Time now) noexcept {
  if (controller_.running()) {  // an earlier run is still winding down: wait for it
    blocked_by_.assign("waiting for the controller to end its run");
    return;
  }
  run_ = Run{};
  run_.what = want;
  run_.phase_since = now;
  if (is_forward(want.kind) && selected_program() != want.program) {
    run_.phase = Phase::kSelecting;
    run_.sent_at = now;
    controller_.select(settings_.programs[static_cast<std::size_t>(want.program)].program).ignore();
    return;
  }
  send_start(now);
}

void SmartToolLogic::send_start(Time now) noexcept {
  run_.phase = Phase::kStarting;
  run_.phase_since = now;
  run_.sent_at = now;
  run_.expected_counter = static_cast<std::uint8_t>(controller_.status().run_counter + 1);
  run_.status_seen_at_send = controller_.status_count();
  const st::Direction direction =
      is_forward(run_.what.kind) ? st::Direction::kForward : st::Direction::kReverse;
  controller_.start(direction).ignore();  // a failure shows as a bus fault; the start then times out
}

void SmartToolLogic::stop(Time now) noexcept {
  if (run_.phase == Phase::kSelecting) {  // nothing was started
    run_ = Run{};
    return;
  }
  controller_.stop().ignore();
  run_.phase = Phase::kStopping;
  run_.phase_since = now;
  run_.sent_at = now;
  run_.status_seen_at_send = controller_.status_count();
}

void SmartToolLogic::advance(Time now) noexcept {
  const bool forward = is_forward(run_.what.kind);
  std::optional<st::RunResult> result = controller_.take_result();
  if (result && (run_.phase == Phase::kIdle || run_.phase == Phase::kSelecting || !forward ||
                 result->run_counter != run_.expected_counter)) {
    note_late_result(*result);
    result.reset();
  }
  if (run_.phase == Phase::kIdle) {
    controller_.take_ack().reset();  // answers to selects we no longer wait for
    return;
  }
  if (result) {
    finish(&*result, 0);
    return;
  }
  const st::Status& status = controller_.status();
  const bool newer_status = controller_.status_count() > run_.status_seen_at_send;
  const bool this_run = status.run_counter == run_.expected_counter;
  if (newer_status && this_run && (status.flags & st::status_flag::kRunning) != 0) run_.confirmed = true;
  if (newer_status && run_.confirmed && this_run && (status.flags & st::status_flag::kRunning) == 0 &&
      !run_.ended) {
    run_.ended = true;
    run_.ended_at = now;
  }

  switch (run_.phase) {
    case Phase::kSelecting: {
      const st::Program& wanted = settings_.programs[static_cast<std::size_t>(run_.what.program)].program;
      const std::optional<st::ProgramAck> ack = controller_.take_ack();
      if (ack && ack->program == wanted) {
        if (ack->code == st::AckCode::kAccepted) {
          acked_program_ = run_.what.program;
          send_start(now);
          return;
        }
        if (ack->code == st::AckCode::kInvalid) {
          program_rejected_[static_cast<std::size_t>(run_.what.program)] = true;
          log_->error("smart tool: the controller rejected program '{}' (number {}) as invalid",
                      settings_.programs[static_cast<std::size_t>(run_.what.program)].name, wanted.number);
          run_ = Run{};
          return;
        }
      }
      if (now - run_.sent_at >= settings_.resend_after) {  // busy, or the ack was lost: ask again
        controller_.select(wanted).ignore();
        run_.sent_at = now;
      }
      return;
    }
    case Phase::kStarting:
      if (run_.confirmed) {
        run_.phase = Phase::kRunning;
        run_.phase_since = now;
      } else if (now - run_.phase_since > settings_.start_timeout) {
        log_->warn("smart tool: the controller did not confirm the start within {:.2f} s",
                   to_seconds(settings_.start_timeout));
        if (run_.what.kind == Kind::kTighten) {
          finish(nullptr, kNotStarted);
        } else {
          refused_ = run_.what.kind;
          run_ = Run{};
        }
      }
      return;
    case Phase::kRunning:
      if (!run_.ended) return;
      if (!forward) {
        run_ = Run{};  // a reverse run ends without a result (alarm, or stopped)
      } else if (now - run_.ended_at > settings_.start_timeout) {
        finish(nullptr, kNoResult);
      }
      return;
    case Phase::kStopping: {
      const bool idle_now = newer_status && (status.flags & st::status_flag::kRunning) == 0;
      if (idle_now && (!forward || !run_.confirmed) && !this_run) {
        // The start never took: there is no result to wait for.
        if (run_.what.kind == Kind::kTighten) {
          finish(nullptr, kNotStarted);
        } else {
          run_ = Run{};
        }
      } else if (idle_now && !forward) {
        run_ = Run{};
      } else if (now - run_.phase_since > settings_.start_timeout && (idle_now || run_.ended)) {
        finish(nullptr, kNoResult | st::nok_reason::kStoppedByCommand);
      } else if (!idle_now && now - run_.sent_at >= settings_.resend_after) {
        controller_.stop().ignore();
        run_.sent_at = now;
      }
      return;
    }
    case Phase::kIdle:
      return;
  }
}

void SmartToolLogic::finish(const st::RunResult* result, std::uint16_t hub_reasons) noexcept {
  const Kind kind = run_.what.kind;
  if (is_forward(kind)) {
    last_ = LastResult{};
    last_.valid = true;
    last_.from_controller = result != nullptr;
    last_.run_id = kind == Kind::kTighten ? run_.what.run_id : 0;
    last_.program = run_.what.program;
    last_.run_counter = run_.expected_counter;
    if (result != nullptr) {
      last_.ok = result->ok;
      last_.torque_cnm = result->torque_cnm;
      last_.angle_ddeg = result->angle_ddeg;
      last_.reasons = result->nok_reasons;
    } else {
      last_.ok = false;
      last_.torque_cnm = controller_.status().torque_cnm;  // the last values seen
      last_.angle_ddeg = controller_.status().angle_ddeg;
      last_.reasons = hub_reasons;
    }
    log_->info("smart tool: run {} ({}) ended {}: {:.2f} Nm, {:.1f} deg{}", last_.run_id,
               settings_.programs[static_cast<std::size_t>(last_.program)].name, last_.ok ? "OK" : "NOK",
               st::to_newton_metres(last_.torque_cnm), st::to_degrees(last_.angle_ddeg),
               last_.from_controller ? "" : " (as the hub saw it)");
  }
  if (kind == Kind::kTighten) {
    has_done_ = true;
    done_run_id_ = run_.what.run_id;
  }
  run_ = Run{};
}

void SmartToolLogic::abort_for_fault() noexcept {
  if (run_.phase == Phase::kSelecting) {  // nothing started
    run_ = Run{};
    return;
  }
  controller_.stop().ignore();  // in case it still hears us
  const std::uint16_t reason = controller_lost_.present() ? kControllerLost : kBusFault;
  if (is_forward(run_.what.kind)) {
    finish(nullptr, reason);
  } else {
    run_ = Run{};
  }
}

void SmartToolLogic::note_late_result(const st::RunResult& result) noexcept {
  // The controller reports a run it lost the link during once it is back (bus-off): it knows the
  // final values better than the hub did.
  if (last_.valid && !last_.from_controller && result.run_counter == last_.run_counter) {
    last_.from_controller = true;
    last_.ok = result.ok;
    last_.torque_cnm = result.torque_cnm;
    last_.angle_ddeg = result.angle_ddeg;
    last_.reasons = result.nok_reasons;
    log_->info("smart tool: the controller's result of run {} came late: {}", last_.run_id,
               last_.ok ? "OK" : "NOK");
  }
}

int SmartToolLogic::selected_program() const noexcept {
  return acked_program_;
}

RunOutput SmartToolLogic::wanted_output() const noexcept {
  if (run_.phase != Phase::kStarting && run_.phase != Phase::kRunning) return RunOutput::kIdle;
  if (run_.ended) return RunOutput::kIdle;
  return is_forward(run_.what.kind) ? RunOutput::kForward : RunOutput::kReverse;
}

std::string_view SmartToolLogic::activity() const noexcept {
  if (run_.phase == Phase::kIdle) return "idle";
  if (run_.phase == Phase::kStopping) return "stopping";
  switch (run_.what.kind) {
    case Kind::kTighten:
      return "tightening";
    case Kind::kLoosen:
      return "loosening";
    case Kind::kManualForward:
      return "manual_forward";
    case Kind::kManualReverse:
      return "manual_reverse";
    case Kind::kNone:
      break;
  }
  return "idle";
}

}  // namespace hubrt::tool_ecu
