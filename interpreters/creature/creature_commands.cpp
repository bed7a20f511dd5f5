#include "interpreters/creature/creature_commands.h"

#include <array>

namespace ontogen {

namespace {

constexpr std::array kCommands = {
    CreatureCommand{"gait", CreatureOp::Gait, 5, 5, "gait(period, duty, stride, lift, height)",
                    "start a creature here, walking along H made level: its root joint stands height units "
                    "above the ground (y = 0) and travels at stride / (duty * period) units a second; period in "
                    "seconds, duty in (0, 1), stride and lift (a swinging foot's highest point) in units"},
    CreatureCommand{"range", CreatureOp::Range, 3, 3, "range(dof, lo, hi)",
                    "the next joint's degree of freedom dof (0, 1, 2) stays in lo..hi deg; a driver or the "
                    "inverse kinematics asking for more is held there and counted in a warning"},
    CreatureCommand{"bend", CreatureOp::Bend, 2, 2, "bend(yaw, pitch)",
                    "a 2-DOF joint (a body segment's): turn H towards L by yaw, then towards U by pitch, deg "
                    "(dof 0 yaw, 1 pitch); the next body segment of the creature"},
    CreatureCommand{"hinge", CreatureOp::Hinge, 1, 1, "hinge(a)",
                    "a 1-DOF joint: turn H towards U by a deg about L (dof 0)"},
    CreatureCommand{"hip", CreatureOp::Hip, 5, 6, "hip(phase, upper, lower, reach, swivel, lift)",
                    "the 3-DOF joint of a leg of two limbs, upper and lower units long, whose foot follows the "
                    "gait: it touches down at phase (cycles), on the ground reach units out along the resting "
                    "H; the leg is solved for the foot with its knee towards U turned by swivel deg about the "
                    "hip-foot line; lift (default: the gait's) scales the swing (dof 0 swing, 1 lift, 2 swivel)"},
    CreatureCommand{"knee", CreatureOp::Knee, 0, 0, "knee",
                    "the 1-DOF joint between the leg's limbs: H turns away from the knee's side by the angle "
                    "the leg's solution asks for (dof 0, 0 deg: straight)"},
    CreatureCommand{"foot", CreatureOp::Foot, 0, 0, "foot", "the end of the leg: a joint that carries nothing"},
    CreatureCommand{"limb", CreatureOp::Limb, 2, 3, "limb(l, r0, r1)",
                    "draw a rigid limb l units along H, a generalized cylinder of radius r0 at its base and r1 "
                    "(default r0) at its tip, swelling between, and move to its end; it moves with the last joint"},
    CreatureCommand{"f", CreatureOp::Move, 1, 1, "f(l)", "move l units along H without drawing"},
    CreatureCommand{"+", CreatureOp::TurnLeft, 1, 1, "+(a)", "turn left by a deg about U: H turns towards L"},
    CreatureCommand{"-", CreatureOp::TurnRight, 1, 1, "-(a)", "turn right by a deg about U"},
    CreatureCommand{"&", CreatureOp::PitchDown, 1, 1, "&(a)", "pitch down by a deg about L: H turns towards -U"},
    CreatureCommand{"^", CreatureOp::PitchUp, 1, 1, "^(a)", "pitch up by a deg about L"},
    CreatureCommand{"\\", CreatureOp::RollLeft, 1, 1, "\\(a)", "roll left by a deg about H: L turns towards -U"},
    CreatureCommand{"/", CreatureOp::RollRight, 1, 1, "/(a)", "roll right by a deg about H"},
    CreatureCommand{"|", CreatureOp::TurnAround, 0, 0, "|", "turn around: 180 deg about U"},
    CreatureCommand{"[", CreatureOp::Push, 0, 0, "[", "push the state: place, frame, joint, leg"},
    CreatureCommand{"]", CreatureOp::Pop, 0, 0, "]", "pop it"},
    CreatureCommand{"color", CreatureOp::Color, 1, 1, "color(i)", "draw with palette colour i (0..15)"},
};

}  // namespace

std::span<const CreatureCommand> creatureCommands() { return kCommands; }

const CreatureCommand* findCreatureCommand(std::string_view name) {
  for (const CreatureCommand& command : kCommands)
    if (command.name == name) return &command;
  return nullptr;
}

}  // namespace ontogen
