using System;

namespace ParticlePhysics.Contacts;

/// <summary>
/// A terrain: heights on a regular grid, the ground below them solid. Row r lies at z = origin.z + r dz, column c at
/// x = origin.x + c dx, and the grid point (r, c) at height origin.y + heights[r, c]; each cell is two triangles split
/// along the diagonal from (r + 1, c) to (r, c + 1).
/// </summary>
/// <remarks>
/// <para>
/// Two triangles per cell rather than the bilinear patch: the distance to a triangle, its gradient and the contact
/// search's tangent bound are exact and in closed form (a bilinear patch's nearest point is the root of a cubic, and
/// its distance is not convex, so the search could only take the Lipschitz bound's slow steps), and a renderer draws
/// the very surface the particles touch. On a planar field (an incline) the two are the same surface.
/// </para>
/// <para>
/// It is a one-sided <see cref="MeshObstacle"/> of those triangles, moved to the origin (the world's axes): impacts at
/// their time within the step, resting, restitution and Coulomb friction as for every obstacle, the cells near a
/// particle found through the mesh's hierarchy. The column below the surface, however deep, is inside, and beside the
/// grid is outside; having no bounds below, it is tested against every particle.
/// </para>
/// </remarks>
public sealed class HeightFieldObstacle : Obstacle
{
    private readonly MeshObstacle _surface;
    private readonly double[,] _heights;

    /// <summary>Creates a height field.</summary>
    /// <param name="origin">Where grid point (0, 0) is at height 0, in metres.</param>
    /// <param name="dx">The spacing of the columns along x, a positive finite number of metres.</param>
    /// <param name="dz">The spacing of the rows along z, a positive finite number of metres.</param>
    /// <param name="heights">heights[r, c]: at least 2 rows and 2 columns of finite heights, in metres (copied).</param>
    /// <param name="restitution">e, 0 to 1 (default 0).</param>
    /// <param name="friction">mu &gt;= 0 (default 0).</param>
    /// <exception cref="ArgumentException">A spacing, a size or a height that is not allowed; the message names it.</exception>
    public HeightFieldObstacle(Vector3d origin, double dx, double dz, double[,] heights, double restitution = 0.0, double friction = 0.0)
        : base(restitution, friction)
    {
        Guard.Finite(origin, nameof(origin));
        Guard.PositiveFinite(dx, nameof(dx));
        Guard.PositiveFinite(dz, nameof(dz));
        Guard.NotNull(heights, nameof(heights));
        var rows = heights.GetLength(0);
        var columns = heights.GetLength(1);
        if (rows < 2 || columns < 2)
        {
            throw new ArgumentException($"heights must have at least 2 rows and 2 columns; got {rows} x {columns}.", nameof(heights));
        }

        var vertices = new double[3 * rows * columns];
        for (var r = 0; r < rows; r++)
        {
            for (var c = 0; c < columns; c++)
            {
                var h = heights[r, c];
                if (!double.IsFinite(h))
                {
                    throw new ArgumentException($"heights[{r}, {c}] must be finite; got {Guard.Format(h)}.", nameof(heights));
                }

                var v = (r * columns) + c;
                vertices[3 * v] = c * dx;
                vertices[(3 * v) + 1] = h;
                vertices[(3 * v) + 2] = r * dz;
            }
        }

        var triangles = new int[6 * (rows - 1) * (columns - 1)];
        var k = 0;
        for (var r = 0; r + 1 < rows; r++)
        {
            for (var c = 0; c + 1 < columns; c++)
            {
                var v = (r * columns) + c;
                var below = v + columns;
                (triangles[k], triangles[k + 1], triangles[k + 2]) = (v, below, v + 1);
                (triangles[k + 3], triangles[k + 4], triangles[k + 5]) = (v + 1, below, below + 1);
                k += 6;
            }
        }

        _heights = (double[,])heights.Clone();
        Dx = dx;
        Dz = dz;
        _surface = new MeshObstacle(new TriangleMesh(vertices, triangles, nameof(heights), nameof(heights)), twoSided: false, restitution, friction)
        {
            Position = origin,
        };
    }

    /// <summary>Where grid point (0, 0) is at height 0 (at <see cref="Obstacle.ReferenceTime"/>).</summary>
    public Vector3d Origin
    {
        get => _surface.Position;
        set => _surface.Position = value;
    }

    /// <summary>The spacing of the columns along x, in metres.</summary>
    public double Dx { get; }

    /// <summary>The spacing of the rows along z, in metres.</summary>
    public double Dz { get; }

    /// <summary>The number of rows (along z).</summary>
    public int Rows => _heights.GetLength(0);

    /// <summary>The number of columns (along x).</summary>
    public int Columns => _heights.GetLength(1);

    /// <summary>The height of grid point (r, c) above the origin, in metres.</summary>
    public double Height(int row, int column) => _heights[row, column];

    /// <inheritdoc />
    public override void Translate(Vector3d offset) => Origin += offset;

    /// <inheritdoc />
    public override double Distance(double x, double y, double z, out double nx, out double ny, out double nz) =>
        _surface.Distance(x, y, z, out nx, out ny, out nz);

    /// <inheritdoc />
    /// <remarks><paramref name="feature"/> receives the triangle: 2 (r (columns - 1) + c) and the one after it for cell (r, c).</remarks>
    public override bool Cast(
        Vector3d origin, Vector3d direction, double radius, double maxDistance, out double distance, out Vector3d normal, out int feature) =>
        _surface.Cast(origin, direction, radius, maxDistance, out distance, out normal, out feature);

    /// <inheritdoc />
    protected override ObstacleShape Describe(Vector3d offset)
    {
        var shape = _surface.Shape;
        return new ObstacleShape(
            ObstacleKind.HeightField, shape.Center + offset, shape.AxisX, shape.AxisY, shape.AxisZ, shape.HalfExtents, shape.Vertices, shape.Triangles);
    }

    /// <inheritdoc />
    internal override double SafeStep(
        double qx, double qy, double qz, double wx, double wy, double wz, double radius, double gap, double rate, double bend, double limit) =>
        _surface.SafeStep(qx, qy, qz, wx, wy, wz, radius, gap, rate, bend, limit);
}
