using System;

namespace ParticlePhysics.Demo.Running;

/// <summary>
/// The period of a swing about x = 0: the times at which particle 0 crosses x = 0 going toward -x, each found by
/// linear interpolation between the steps around it, and their mean spacing (NaN until two crossings).
/// </summary>
internal sealed class PeriodObserver : IStepObserver
{
    private double _previousTime;
    private double _previousX = double.NaN;
    private double _first = double.NaN;
    private double _last = double.NaN;
    private int _crossings;

    /// <summary>The mean time between crossings in the same direction, in s, or NaN before the second one.</summary>
    public double Period => _crossings >= 2 ? (_last - _first) / (_crossings - 1) : double.NaN;

    public void AfterStep(ParticleWorld world)
    {
        var x = world.GetPosition(0).X;
        var time = world.Time;
        if (double.IsNaN(_previousX))
        {
            // The first step: the start is x at t = 0, before any step.
            _previousX = x;
            _previousTime = time;
            return;
        }

        if (_previousX > 0 && x <= 0)
        {
            var crossing = _previousTime + ((time - _previousTime) * _previousX / (_previousX - x));
            _first = _crossings == 0 ? crossing : _first;
            _last = crossing;
            _crossings++;
        }

        _previousX = x;
        _previousTime = time;
    }
}
